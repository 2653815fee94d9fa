"""Shared measurement helpers of the Python benchmarks (bench/*.py).

- `measure(f, repeat, number)`: the median time per call over `repeat`
  rounds of `number` calls, with the fastest and slowest round (the
  spread); medians resist the other jobs of a shared machine better than a
  single run, and the spread shows how much they disturbed this one.
- `peak_rss(f)`: the peak resident memory that one call of f adds to the
  process, from the kernel's own high-water mark (VmHWM, reset through
  /proc/self/clear_refs): it counts every allocation (NumPy's, libmcstat's
  malloc, threads' stacks), not only those tracemalloc sees.  Before the
  call, malloc_trim(0) hands the memory that glibc keeps from earlier cases
  back to the kernel, so that reusing it shows as new resident pages.
- `machine()`: CPU model, core count, load average, for the headers.

No benchmark asserts a time: numbers are written down, never checked.
"""
import ctypes
import ctypes.util
import os
import platform
import statistics
import time


class Timing:
    __slots__ = ("median", "lo", "hi", "rounds")

    def __init__(self, per_call):
        self.median = statistics.median(per_call)
        self.lo, self.hi = min(per_call), max(per_call)
        self.rounds = len(per_call)

    def fmt(self, unit=None):
        """'1.23 us [1.20-1.40]': median [fastest-slowest round]."""
        scale, unit = _unit(self.median, unit)
        return f"{num(self.median * scale)} {unit} [{num(self.lo * scale)}-{num(self.hi * scale)}]"


def num(v):
    """About three significant digits, never an exponent."""
    if v >= 100:
        return f"{v:.0f}"
    if v >= 10:
        return f"{v:.1f}"
    return f"{v:.3g}"


def _unit(t, unit=None):
    units = {"s": 1.0, "ms": 1e3, "us": 1e6, "ns": 1e9}
    if unit is None:
        unit = "s" if t >= 1 else "ms" if t >= 1e-3 else "us" if t >= 1e-6 else "ns"
    return units[unit], unit


def measure(f, repeat=7, number=1):
    per_call = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            f()
        per_call.append((time.perf_counter() - t0) / number)
    return Timing(per_call)


def _status_kib(*keys):
    out = {}
    with open("/proc/self/status") as fh:
        for line in fh:
            k = line.split(":", 1)[0]
            if k in keys:
                out[k] = int(line.split()[1])
    return out


def _trim():
    try:
        ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass


def peak_rss(f):
    """Bytes of resident memory above the starting level at the peak of one
    call of f; None where /proc cannot tell (not Linux)."""
    _trim()
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")  # resets VmHWM to the current VmRSS
        before = _status_kib("VmRSS")["VmRSS"]
    except (OSError, KeyError):
        f()
        return None
    f()
    return max(0, _status_kib("VmHWM")["VmHWM"] - before) * 1024


def fmt_bytes(b):
    if b is None:
        return "n/a"
    if b < 1 << 20:
        return f"{b / 1024:.0f} KiB"
    return f"{b / 2**20:.1f} MiB"


def cpu_model():
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"


def load():
    try:
        return os.getloadavg()
    except OSError:
        return (float("nan"),) * 3


def machine():
    l1, l5, l15 = load()
    return (f"{cpu_model()}, {os.cpu_count()} cores, {platform.system()} {platform.release()}; "
            f"load average {l1:.2f} / {l5:.2f} / {l15:.2f} (1 / 5 / 15 min)")
