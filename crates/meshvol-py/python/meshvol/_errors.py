"""The errors for a file that cannot be opened: the OSError subclass Python raises for
the same failure (so `except FileNotFoundError` and `except OSError` catch them, with
errno, strerror and filename), and also meshvol.ReadError (so a meshvol.MeshError), as
every error reading a file was before."""

import os

from ._meshvol import ReadError

__all__ = ["MeshOSError", "MeshFileNotFoundError", "MeshPermissionError", "MeshIsADirectoryError"]


class MeshOSError(OSError, ReadError):
    """A mesh file could not be opened or read: an OSError and a meshvol.ReadError.
    Attributes: errno, strerror, filename (OSError's) and path, reason (ReadError's;
    location, line, byte and face are None). The message is meshvol's, 'PATH: REASON'
    ('part.stl: No such file or directory'), as every ReadError's."""

    def __str__(self) -> str:
        if self.filename is None or self.strerror is None:
            return super().__str__()
        return f"{os.fsdecode(self.filename)}: {self.strerror}"


class MeshFileNotFoundError(FileNotFoundError, MeshOSError):
    """The file does not exist (a FileNotFoundError and a meshvol.ReadError)."""


class MeshPermissionError(PermissionError, MeshOSError):
    """The file cannot be read with the permissions given (a PermissionError and a
    meshvol.ReadError)."""


class MeshIsADirectoryError(IsADirectoryError, MeshOSError):
    """The path is a directory (an IsADirectoryError and a meshvol.ReadError)."""


for _class in (MeshOSError, MeshFileNotFoundError, MeshPermissionError, MeshIsADirectoryError):
    _class.__module__ = "meshvol"
