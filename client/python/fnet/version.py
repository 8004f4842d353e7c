"""fnet's version: the same as CMake's project(fnet VERSION ...), which a test checks."""

__version__ = "0.1.0"
