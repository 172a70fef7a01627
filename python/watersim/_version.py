"""The installed package's version, in a module of its own so that any module can import it
without importing the package's ``__init__`` (which imports almost every module)."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__: str = version("watersim")
except PackageNotFoundError:  # pragma: no cover - running from a source tree without install
    __version__ = "0.0.0+unknown"
