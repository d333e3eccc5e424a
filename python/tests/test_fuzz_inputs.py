"""The Hypothesis fuzz targets of fuzz_inputs.py, each on a few hundred inputs (`make
fuzz-python` runs them on 1M in total): no bad input ends in anything but a one-line error."""

import pytest

pytest.importorskip("hypothesis")
pytestmark = pytest.mark.needs_torch_numpy  # export_sb3 and the policy.pth reader use torch

import fuzz_inputs  # noqa: E402

SHORT_RUN_EXAMPLES = 150


@pytest.mark.parametrize("name", sorted(fuzz_inputs.TARGETS))
def test_target_finds_no_failure(name):
    fuzz_inputs.run(name, SHORT_RUN_EXAMPLES)


def test_oracle_refuses_a_multi_line_message():
    def raises():
        raise ValueError("first line\nsecond line")

    with pytest.raises(AssertionError, match="second line"):
        fuzz_inputs.expect_one_line_error(raises)


def test_oracle_refuses_an_undocumented_kind():
    def raises():
        raise RecursionError("maximum recursion depth exceeded")

    with pytest.raises(RecursionError):
        fuzz_inputs.expect_one_line_error(raises)
