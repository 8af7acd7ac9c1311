# Type stub of the C++ extension module (cpp_kernels/src, built by scikit-build-core).
# Its entry points are documented, with shapes and packing order, by the Python
# modules that call them: tribofx.projection, tribofx.lubrication_projection,
# tribofx.two_body and tribofx.petsc_insert.
from typing import Any

def __getattr__(name: str) -> Any: ...
