"""Data-parallel training over the GPUs of one machine: `python3 parallel.py N train.py ARGS...`
runs N processes of `train.py`, each on its own GPU with its own share of the sequences
(`data.load_split`'s `part`) and its own windows; their gradients are averaged before every step,
so the model sees N times the batch, and the first process alone validates, decides when the time is
up and writes the weights. Started plainly (no `WORLD_SIZE` in the environment), every function
here is the single-process identity and no process group is made."""

import os
import socket
import subprocess
import sys

import torch
import torch.distributed as dist


class Group:
    """This process's place: `rank` of `world` processes, and its `device`."""

    def __init__(self):
        self.world = int(os.environ.get("WORLD_SIZE", "1"))
        self.rank = int(os.environ.get("RANK", "0"))
        if self.world > 1:
            local = int(os.environ["LOCAL_RANK"])
            if torch.cuda.is_available():
                if local >= torch.cuda.device_count():
                    raise SystemExit(
                        f"process {local} of {self.world} has no GPU of its own: "
                        f"{torch.cuda.device_count()} visible (CUDA_VISIBLE_DEVICES)"
                    )
                torch.cuda.set_device(local)
                self.device = f"cuda:{local}"
                dist.init_process_group("nccl")
            else:
                self.device = "cpu"
                dist.init_process_group("gloo")
        else:
            self.device = "cuda" if torch.cuda.is_available() else "cpu"

    @property
    def first(self):
        """Whether this is the process that validates, logs and writes the weights."""
        return self.rank == 0

    def share(self):
        """This process's share of the sequences, as `data.load_split` takes it."""
        return (self.rank, self.world)

    def progress(self, fraction):
        """The first process's `fraction` of the time budget, the same in every process, so that all
        take the same learning rate and stop after the same step."""
        if self.world == 1:
            return fraction
        value = torch.tensor([fraction], dtype=torch.float64, device=self.device)
        dist.broadcast(value, 0)
        return float(value.item())

    def all_finite(self, loss):
        """Whether `loss` is finite in every process (a step is taken by all or by none)."""
        finite = torch.isfinite(loss.detach()).to(torch.int32).reshape(1)
        if self.world > 1:
            dist.all_reduce(finite, op=dist.ReduceOp.MIN)
        return bool(finite.item())

    def same_start(self, model):
        """Every process's parameters set to the first's."""
        if self.world > 1:
            for p in model.parameters():
                dist.broadcast(p.data, 0)

    def average_gradients(self, model):
        """The parameters' gradients averaged over the processes, in one flat reduction."""
        if self.world == 1:
            return
        for p in model.parameters():
            if p.grad is None:
                p.grad = torch.zeros_like(p)
        grads = [p.grad for p in model.parameters()]
        flat = torch.cat([g.reshape(-1) for g in grads])
        dist.all_reduce(flat)
        flat /= self.world
        offset = 0
        for g in grads:
            g.copy_(flat[offset : offset + g.numel()].view_as(g))
            offset += g.numel()

    def wait(self):
        """All processes here before any goes on (the first has validated or written)."""
        if self.world > 1:
            dist.barrier()

    def close(self):
        """The process group taken down."""
        if self.world > 1:
            dist.destroy_process_group()


def launch(processes, command):
    """Runs `processes` copies of the Python script and arguments `command`, process K on GPU K
    (of those CUDA_VISIBLE_DEVICES names), joined in one group on a free local port; if one fails
    the others are stopped. Returns the first non-zero exit status, else 0. (torchrun would take the
    script's own `--log` for an abbreviation of its options.)"""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    children = []
    for rank in range(processes):
        env = dict(
            os.environ,
            WORLD_SIZE=str(processes),
            RANK=str(rank),
            LOCAL_RANK=str(rank),
            MASTER_ADDR="127.0.0.1",
            MASTER_PORT=str(port),
        )
        children.append(subprocess.Popen([sys.executable, *command], env=env))
    status = 0
    while children:
        for child in list(children):
            code = child.poll()
            if code is None:
                continue
            children.remove(child)
            if code and not status:
                status = code
                for other in children:
                    other.terminate()
        if children:
            try:
                children[0].wait(timeout=1)
            except subprocess.TimeoutExpired:
                pass
    return status


if __name__ == "__main__":
    if len(sys.argv) < 3 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        raise SystemExit("usage: python3 parallel.py PROCESSES SCRIPT [ARGS...]")
    sys.exit(launch(int(sys.argv[1]), sys.argv[2:]))
