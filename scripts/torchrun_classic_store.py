#!/usr/bin/env python3
"""torchrun whose rendezvous store uses TCPStore's classic backend where PyTorch lacks libuv.

PyTorch 2.4 made libuv the default backend of TCPStore, and torchrun's rendezvous handlers
(static, c10d, dynamic) create their store without passing use_libuv, so they ignore
USE_LIBUV=0 (pytorch/pytorch issue 178600). Debian 13's python3-torch (2.6) is built without
libuv: every torchrun there fails before starting a worker, with "use_libuv was requested but
PyTorch was build without libuv support". Where that is so, this script makes the stores ask
for the classic backend (the one upkie-rl's ranks use, and the only one of older PyTorch);
elsewhere it is torchrun unchanged. It takes torchrun's arguments; run it with the Python
that has torch (torchrun's own, /usr/bin/python3 on Debian):

    /usr/bin/python3 scripts/torchrun_classic_store.py --nproc_per_node 2 --redirects 1 \\
        --tee 1 --no_python upkie-rl train --config configs/pendulum.yaml
"""

import os
import sys
from datetime import timedelta

import torch.distributed as dist


def libuv_store_missing() -> bool:
    """Whether this TCPStore asks for libuv by default but was built without it."""
    if "use_libuv" not in (dist.TCPStore.__init__.__doc__ or ""):
        return False  # PyTorch before 2.2: the classic backend only, nothing to change
    try:
        probe = dist.TCPStore(
            "127.0.0.1", 0, 1, True, timedelta(seconds=10), wait_for_workers=False
        )
    except RuntimeError as error:
        if "libuv" in str(error):
            return True
        raise
    del probe
    return False


def use_classic_store() -> None:
    """Makes every TCPStore that torchrun creates default to the classic backend."""

    class ClassicTCPStore(dist.TCPStore):  # a subclass: isinstance checks still hold
        def __init__(self, *args, **kwargs):
            kwargs.setdefault("use_libuv", False)
            super().__init__(*args, **kwargs)

    from torch.distributed.elastic.rendezvous import (
        c10d_rendezvous_backend,
        static_tcp_rendezvous,
    )

    # Those two modules imported the name itself; the others look it up in dist.
    for module in (dist, c10d_rendezvous_backend, static_tcp_rendezvous):
        module.TCPStore = ClassicTCPStore
    os.environ["USE_LIBUV"] = "0"  # the stores that do read it (init_process_group's)


if __name__ == "__main__":
    if libuv_store_missing():
        use_classic_store()
    from torch.distributed.run import main

    sys.argv[0] = "torchrun"
    sys.exit(main())
