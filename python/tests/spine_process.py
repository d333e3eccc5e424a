"""`upkie-rl spine` in a subprocess, for the tests that drive it from Python."""

import os
import signal
import subprocess
import time
import uuid
from pathlib import Path


def cli_path() -> Path:
    if "UPKIE_RL_CLI" in os.environ:
        return Path(os.environ["UPKIE_RL_CLI"])
    build_dir = os.environ.get("UPKIE_RL_BUILD_DIR", "build")
    return Path(build_dir) / "upkie-rl"


class SpineProcess:
    """`upkie-rl spine` in a subprocess on a fresh shared-memory name."""

    def __init__(self, *extra_args: str):
        self.shm_name = f"/upkie_rl_pytest_{os.getpid()}_{uuid.uuid4().hex[:8]}"
        self.shm_path = Path("/dev/shm") / self.shm_name.lstrip("/")
        command = [str(cli_path()), "spine", "--shm-name", self.shm_name]
        self.process = subprocess.Popen(
            command + list(extra_args),
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        deadline = time.monotonic() + 30.0
        while not self.shm_path.exists():
            if self.process.poll() is not None:
                output = self.process.stdout.read()
                raise RuntimeError(f"spine exited early:\n{output}")
            if time.monotonic() > deadline:
                self.stop()
                raise RuntimeError("spine did not create its shared memory")
            time.sleep(0.01)

    def stop(self) -> int:
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(timeout=10.0)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        if self.shm_path.exists():  # never leave it behind, even on failure
            self.shm_path.unlink()
            raise AssertionError(f"spine left {self.shm_path} behind")
        return self.process.returncode
