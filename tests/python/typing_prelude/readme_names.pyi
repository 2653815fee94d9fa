# The names README.md's Python examples take as given (the user's data), with
# the types a user would have: test_typing.py type-checks every example
# against them.
from typing import Any, Callable, List, Tuple

import numpy as np
import numpy.typing as npt

import mcstat as mcstat  # the examples after the first assume it imported

_A = npt.NDArray[np.float64]

new: _A
trusted: _A
before: _A
after: _A
x: _A
img: _A
reference_img: _A
renders: npt.NDArray[np.float32]
direction: Callable[[float], _A]
estimates: Callable[[int, int], _A]
reference: float
reference_renders: npt.NDArray[np.float32]
batch: _A
primary: _A
pairs: List[Tuple[_A, _A]]
pvalues: _A
rejections: int
wo: _A
wi: _A
sample: Callable[..., Any]
eval: Callable[..., Any]
pdf: Callable[..., Any]
stack: _A
blobs: List[bytes]
error_total: mcstat.MomentsArray
new_total: mcstat.MomentsArray
trusted_total: mcstat.MomentsArray
