"""meshvol.Grid: the cell volumes of Mesh.grid() with where the cells are; meshvol.CutCells:
the cut-cell geometry of Mesh.cells()."""

from __future__ import annotations

from typing import Any, Optional, Tuple

import numpy as np
from numpy.lib.mixins import NDArrayOperatorsMixin

__all__ = ["CutCells", "Grid"]


class Grid(NDArrayOperatorsMixin):
    """The volume of a solid in each cell of a regular grid (what Mesh.grid returns).

    values: the (nx, ny, nz) float64 array (a cell's volume, or its filled fraction with
    fraction=True). Cell (i, j, k) spans origin + (i, j, k) * spacing to origin + (i + 1,
    j + 1, k + 1) * spacing; for a block (region=...), origin is the block's first
    cell's corner. bounds is the (2, 3) box the cells cover: (origin, origin + shape *
    spacing) (with pitch=, larger than the box asked for: whole cells).

    A Grid is used as its array: np.asarray(grid) is grid.values (no copy), NumPy
    functions and operators take it (grid.sum(), grid == other, grid[1:2] give arrays),
    and the array's attributes are its attributes (shape, dtype, ravel, ...).
    """

    __slots__ = ("_values", "_origin", "_spacing", "_fraction", "_timings")

    def __init__(
        self,
        values: np.ndarray,
        origin: Any,
        spacing: Any,
        fraction: bool = False,
    ) -> None:
        self._values = np.asarray(values, dtype=np.float64)
        if self._values.ndim != 3:
            raise ValueError(f"values must be a 3-dimensional array; got shape {self._values.shape}")
        self._origin = np.array(origin, dtype=np.float64).reshape(3)
        self._spacing = np.array(spacing, dtype=np.float64).reshape(3)
        self._fraction = bool(fraction)
        self._timings: Optional[list] = None
        for a in (self._origin, self._spacing):
            a.setflags(write=False)

    @property
    def timings(self) -> list:
        """With Mesh.grid(timings=True): the stages' {stage, wall_s, cpu_s, peak_mb} (else absent)."""
        if self._timings is None:
            raise AttributeError("timings: ask Mesh.grid(..., timings=True)")
        return self._timings

    @property
    def values(self) -> np.ndarray:
        """The (nx, ny, nz) float64 array of cell volumes (or fractions)."""
        return self._values

    @property
    def origin(self) -> np.ndarray:
        """The lower corner of cell (0, 0, 0), a float64 array of 3."""
        return self._origin

    @property
    def spacing(self) -> np.ndarray:
        """The cells' size along x, y and z, a float64 array of 3."""
        return self._spacing

    @property
    def bounds(self) -> np.ndarray:
        """The (2, 3) box the cells cover: [origin, origin + shape * spacing]."""
        upper = self._origin + np.array(self._values.shape, dtype=np.float64) * self._spacing
        return np.array([self._origin, upper])

    @property
    def shape(self) -> Tuple[int, ...]:
        """The cell counts (nx, ny, nz): values.shape."""
        return self._values.shape

    @property
    def dtype(self) -> Any:
        """float64: values.dtype."""
        return self._values.dtype

    @property
    def fraction(self) -> bool:
        """Whether values are fractions of each cell's volume (fraction=True)."""
        return self._fraction

    @property
    def cell_volume(self) -> float:
        """The volume of one cell."""
        return float(np.prod(self._spacing))

    def centers(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The cells' centre coordinates along x, y and z (three 1-D arrays)."""
        return tuple(  # type: ignore[return-value]
            self._origin[a] + (np.arange(n) + 0.5) * self._spacing[a]
            for a, n in enumerate(self._values.shape)
        )

    def to_xarray(self, name: Optional[str] = None) -> Any:
        """The grid as an xarray.DataArray: dims ('x', 'y', 'z'), the cells' centres as
        coordinates, origin, spacing and what the values are as attributes. Needs
        xarray (pip install xarray)."""
        try:
            import xarray
        except ImportError as e:
            raise ImportError(
                "Grid.to_xarray() needs xarray, which is not installed: pip install xarray"
            ) from e
        x, y, z = self.centers()
        return xarray.DataArray(
            self._values,
            dims=("x", "y", "z"),
            coords={"x": x, "y": y, "z": z},
            name=name or ("fraction" if self._fraction else "volume"),
            attrs={
                "origin": self._origin.tolist(),
                "spacing": self._spacing.tolist(),
                "values": "fraction" if self._fraction else "volume",
            },
        )

    # The array protocol: NumPy code that took the bare array keeps working.
    def __array__(self, dtype: Any = None, copy: Optional[bool] = None) -> np.ndarray:
        if copy:
            return np.array(self._values, dtype=dtype, copy=True)
        if dtype is None:
            return self._values
        return self._values.astype(dtype, copy=False)

    def __array_ufunc__(self, ufunc: Any, method: str, *inputs: Any, **kwargs: Any) -> Any:
        unwrap = tuple(x._values if isinstance(x, Grid) else x for x in inputs)
        if "out" in kwargs:
            kwargs["out"] = tuple(x._values if isinstance(x, Grid) else x for x in kwargs["out"])
        return getattr(ufunc, method)(*unwrap, **kwargs)

    def __array_function__(self, func: Any, types: Any, args: Any, kwargs: Any) -> Any:
        def unwrap(x: Any) -> Any:
            if isinstance(x, Grid):
                return x._values
            if isinstance(x, (list, tuple)):
                return type(x)(unwrap(y) for y in x)
            return x

        return func(*unwrap(args), **{k: unwrap(v) for k, v in kwargs.items()})

    def __getitem__(self, key: Any) -> Any:
        return self._values[key]

    def __len__(self) -> int:
        return len(self._values)

    def __iter__(self) -> Any:
        return iter(self._values)

    def __getattr__(self, name: str) -> Any:
        # shape, dtype, ndim, size, sum, ravel, ...: the array's.
        if name.startswith("__") or name in Grid.__slots__:
            raise AttributeError(name)
        return getattr(self._values, name)

    def __dir__(self) -> Any:
        return sorted(set(object.__dir__(self)) | set(dir(self._values)))

    def __reduce__(self) -> Any:
        return (Grid, (self._values, self._origin, self._spacing, self._fraction))

    def __repr__(self) -> str:
        nx, ny, nz = self._values.shape
        what = "fraction" if self._fraction else "volume"
        return (
            f"Grid(shape=({nx}, {ny}, {nz}), origin={self._origin.tolist()}, "
            f"spacing={self._spacing.tolist()}, values='{what}')"
        )


class CutCells(dict):  # type: ignore[type-arg]
    """The cut-cell geometry of a solid on a grid (what Mesh.cells returns): a dict of
    float64 arrays, named as `meshvol grid --moments` writes them (docs/cells.md).

    Cell arrays, shape (nx, ny, nz) or (nx, ny, nz, 3): volume, fraction, centroid,
    boundary_area, boundary_vector, boundary_centroid. Face arrays: aperture_x
    (nx + 1, ny, nz), aperture_y (nx, ny + 1, nz), aperture_z (nx, ny, nz + 1), the
    fraction of each cell face inside the solid. With second_moments=True, inertia
    (nx, ny, nz, 3, 3): each cell's solid's inertia tensor about its centroid (unit
    density, as mass_properties' inertia). With face_centroids=True, aperture_x_centroid
    (nx + 1, ny, nz, 3), aperture_y_centroid, aperture_z_centroid: the centroid of each
    face's part inside the solid, NaN where the aperture is 0. origin and spacing place
    the cells as Grid's do.
    """

    origin: np.ndarray
    """The lower corner of cell (0, 0, 0), a float64 array of 3."""
    spacing: np.ndarray
    """The cells' size along x, y and z, a float64 array of 3."""

    def __init__(self, arrays: Any, origin: Any, spacing: Any) -> None:
        super().__init__(arrays)
        self.origin = np.array(origin, dtype=np.float64).reshape(3)
        self.spacing = np.array(spacing, dtype=np.float64).reshape(3)

    @property
    def shape(self) -> Tuple[int, ...]:
        """The cell counts (nx, ny, nz)."""
        return tuple(self["volume"].shape)

    def to_xarray(self) -> Any:
        """The arrays as an xarray.Dataset: cell arrays on dims ('x', 'y', 'z') (the
        cells' centres) and 'component' for vectors; each aperture on its faces' dims
        ('x_face', 'y', 'z'), ... (the planes' coordinates). Needs xarray."""
        try:
            import xarray
        except ImportError as e:
            raise ImportError(
                "CutCells.to_xarray() needs xarray, which is not installed: pip install xarray"
            ) from e
        n = self.shape
        centres = [self.origin[a] + (np.arange(n[a]) + 0.5) * self.spacing[a] for a in range(3)]
        planes = [self.origin[a] + np.arange(n[a] + 1) * self.spacing[a] for a in range(3)]
        cell_dims = ("x", "y", "z")
        variables = {}
        # Trailing axes: a vector's component; a tensor's row and column.
        trailing = {3: (), 4: ("component",), 5: ("row", "column")}
        for name, values in self.items():
            if name.startswith("aperture_"):
                a = "xyz".index(name[len("aperture_")])
                dims = tuple(f"{d}_face" if i == a else d for i, d in enumerate(cell_dims))
            else:
                dims = cell_dims
            variables[name] = (dims + trailing[values.ndim], values)
        coords = {d: centres[a] for a, d in enumerate(cell_dims)}
        coords.update({f"{d}_face": planes[a] for a, d in enumerate(cell_dims)})
        for axis in ("component", "row", "column"):
            coords[axis] = ["x", "y", "z"]
        attrs = {"origin": self.origin.tolist(), "spacing": self.spacing.tolist()}
        return xarray.Dataset(variables, coords=coords, attrs=attrs)

    def __reduce__(self) -> Any:
        return (CutCells, (dict(self), self.origin, self.spacing))

    def __repr__(self) -> str:
        nx, ny, nz = self.shape
        return (
            f"CutCells(shape=({nx}, {ny}, {nz}), origin={self.origin.tolist()}, "
            f"spacing={self.spacing.tolist()}, arrays={sorted(self)})"
        )
