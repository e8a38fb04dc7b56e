"""Type stubs of the compiled module (src/lib.rs); use the wrappers in ``scratchwave``."""

from typing import Dict, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

class InputError(ValueError):
    """Rejected input: the message names the field (JSON path) or argument."""

class NativeScratchSet:
    @staticmethod
    def from_json(text: str, base_dir: Optional[str] = None) -> "NativeScratchSet": ...
    @staticmethod
    def from_rows(rows: npt.NDArray[np.float64], triangle: list[bool]) -> "NativeScratchSet": ...
    def __len__(self) -> int: ...

class NativeBsdf:
    @staticmethod
    def from_json(
        text: str, base_dir: Optional[str] = None, scratches: Optional[NativeScratchSet] = None
    ) -> "NativeBsdf": ...
    def scratch_count(self) -> int: ...
    def eval(
        self,
        wo: npt.NDArray[np.float32],
        wi: npt.NDArray[np.float32],
        x_um: Optional[npt.NDArray[np.float32]],
        footprint: Optional[npt.NDArray[np.float32]],
        lambda_nm: Optional[npt.NDArray[np.float32]],
        lambda_count: int,
    ) -> npt.NDArray[np.float32]: ...
    def pdf(
        self,
        wo: npt.NDArray[np.float32],
        wi: npt.NDArray[np.float32],
        x_um: Optional[npt.NDArray[np.float32]],
        footprint: Optional[npt.NDArray[np.float32]],
        lambda_nm: Optional[npt.NDArray[np.float32]],
        lambda_count: int,
    ) -> npt.NDArray[np.float32]: ...
    def sample(
        self,
        wo: npt.NDArray[np.float32],
        u: npt.NDArray[np.float32],
        x_um: Optional[npt.NDArray[np.float32]],
        footprint: Optional[npt.NDArray[np.float32]],
        lambda_nm: Optional[npt.NDArray[np.float32]],
        lambda_count: int,
    ) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.float32], npt.NDArray[np.float32]]: ...

def render(
    text: str,
    name: str,
    base_dir: str,
    backend: str,
    region: Optional[Tuple[int, int, int, int]] = None,
) -> Tuple[npt.NDArray[np.float32], int, int, Dict[str, float]]: ...
def table(text: str, backend: str = "cpu") -> npt.NDArray[np.float32]: ...
