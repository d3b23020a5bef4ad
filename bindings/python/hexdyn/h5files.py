"""What every reader of hexdyn's files shares, with h5py only: paths and errors, opening a
file, the one read loop, the schema and version of /meta, and the checks of datasets
against their declarations (hexdyn.schema). hexdyn.results puts them together per file kind.
"""

import os
import stat

import h5py
import numpy as np
import yaml

from .schema import DECLARED


# ---------------------------------------------------------------------------- paths, errors
def checked_path(path):
    """os.fspath(path) (a str or bytes path; TypeError for anything else), after refusing a
    path with a NUL character with a ValueError in one line: the C++ side and the operating
    system stop at the first NUL, so "paper.yaml\\0junk" would name paper.yaml. Every function of
    the package that takes a path calls this first."""
    text = os.fspath(path)
    if ("\0" if isinstance(text, str) else b"\0") in text:
        raise ValueError(f"path {text!r} contains a NUL character")
    return text


def decode_text(value):
    """str from an HDF5 string value (h5py gives str or bytes depending on storage; a 0-d
    array holds one). The one decoder of hexdyn's HDF5 text: the readers and analysis/ use it."""
    if isinstance(value, bytes):
        return value.decode("utf-8")
    if isinstance(value, np.ndarray) and value.shape == ():
        return decode_text(value[()])
    return value


def one_line(text):
    """`text` on one line, as hexdyn's messages are (core/errors.hpp one_line)."""
    return str(text).replace("\n", "\\n").replace("\r", "\\r")


def io_error(message):
    """hexdyn.IoError (an OSError) when the compiled part is there, else OSError; the
    message on one line."""
    message = one_line(message)
    try:
        from . import _hexdyn
        return _hexdyn.IoError(message)
    except ImportError:
        return OSError(message)


def _reason(error):
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


def check_regular_file(path):
    """Raises hexdyn.IoError with one line unless `path` names a regular file (a link to one
    counts): a FIFO, a device, a socket or a directory is refused before anything opens it
    (opening a FIFO for reading waits for a writer, for ever). ValueError for a path with a
    NUL character (checked_path)."""
    path = checked_path(path)
    try:
        mode = os.stat(path).st_mode
    except OSError as e:
        raise io_error(f"{os.fsdecode(path)}: cannot be read: {e.strerror}") from None
    if stat.S_ISREG(mode):
        return
    kind = ("a FIFO" if stat.S_ISFIFO(mode) else "a directory" if stat.S_ISDIR(mode) else
            "a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else
            "a socket" if stat.S_ISSOCK(mode) else "a special file")
    raise io_error(f"{os.fsdecode(path)}: is {kind}, not a regular file")


def open_h5(path):
    """h5py.File(path, "r") of a regular file (check_regular_file); a file HDF5 cannot open
    (not HDF5, truncated, damaged) raises hexdyn.IoError with one line naming it."""
    path = checked_path(path)
    check_regular_file(path)
    try:
        return h5py.File(path, "r")
    except OSError as e:
        raise io_error(f"{os.fsdecode(path)}: cannot be read as HDF5: {_reason(e)}") from None


def file_identity(path):
    """What tells a file apart from another, and from itself after a change."""
    st = os.stat(path)
    return (st.st_dev, st.st_ino, st.st_size, st.st_mtime_ns)


# ---------------------------------------------------------------------------- reading
def is_group_coordinate(path, obj, root):
    """True for a group coordinate (docs/user/output.md#dimensions-and-coordinates): in a
    group below `root` (a file, or a sweep's kept run /runs/<id>), the copy G/D of the root's
    coordinate D that the group's datasets are attached to, so that the group opened alone
    has its coordinates. `path` is relative to `root` ("/joints/time"). It is an HDF5
    dimension scale, declared by no table of the schema, and `root` has a dataset of its
    name. The readers leave it out: the root's D is read once."""
    if path.count("/") < 2 or path in DECLARED or not isinstance(obj, h5py.Dataset):
        return False
    return (isinstance(root.get(path.rsplit("/", 1)[1]), h5py.Dataset)  # relative to root
            and bool(h5py.h5ds.is_scale(obj.id)))


def datasets_below(root, under=""):
    """{"/path": h5py.Dataset} of every dataset below the group `under` of `root` (a file or
    a kept run's group; "" root itself), paths relative to `root` ("/scenarios/energy"),
    group coordinates (is_group_coordinate) left out."""
    prefix = "/" + under.strip("/") if under.strip("/") else ""
    out = {}

    def visit(name, obj):
        path = f"{prefix}/{name}"
        if isinstance(obj, h5py.Dataset) and not is_group_coordinate(path, obj, root):
            out[path] = obj
    (root[prefix[1:]] if prefix else root).visititems(visit)
    return out


def read_checked(ds, source):
    """A dataset's values: numbers as h5py gives them, text as str, a list of texts as a list
    of str. A failed read (a damaged file) raises hexdyn.IoError naming the dataset."""
    try:
        if h5py.check_string_dtype(ds.dtype) is None:
            return ds[()]
        values = ds.asstr()[()]
        if ds.shape == ():
            return decode_text(values)
        return [decode_text(v) for v in np.asarray(values).ravel()]
    except (OSError, UnicodeDecodeError) as e:
        raise io_error(f"{source}: dataset {ds.name} cannot be read: {_reason(e)}") from None


def read_datasets(datasets, source, text_arrays=False):
    """The one read loop of the readers: (data, units, shapes) of `datasets` ({path:
    h5py.Dataset}), each by path: its values (read_checked; with `text_arrays` a list of
    texts as a numpy array of str of the dataset's shape), its shape, and its `units`
    attribute for those that have one."""
    data, units, shapes = {}, {}, {}
    for path, ds in datasets.items():
        value = read_checked(ds, source)
        if text_arrays and isinstance(value, list):
            value = np.array(value, dtype=object).reshape(ds.shape)
        data[path] = value
        shapes[path] = tuple(ds.shape)
        if "units" in ds.attrs:
            units[path] = decode_text(ds.attrs["units"])
    return data, units, shapes


def python_value(value):
    """An attribute's value as Python has it: str for text, int or float for a number."""
    value = decode_text(value)
    return value.item() if isinstance(value, np.generic) else value


def meta_attributes(group):
    """The /meta attributes of a file (or of a kept run's group) as Python values."""
    return {key: python_value(value) for key, value in group["meta"].attrs.items()}


def group_attributes(group, skip):
    """{"/GROUP/NAME": value} of the attributes of the groups below `group` but `skip`
    (paths relative to `group`), values as Python values."""
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Group) and "/" + name != skip:
            for key, value in obj.attrs.items():
                out[f"/{name}/{key}"] = python_value(value)
    group.visititems(visit)
    return out


def yaml_attribute(meta, name, source):
    """The /meta attribute `name` parsed as YAML (a dict; {} when absent or empty);
    ValueError naming the file when it is not YAML."""
    try:
        return yaml.safe_load(meta.get(name, "") or "") or {}
    except yaml.YAMLError as e:
        raise ValueError(f"{source}: /meta {name} is not valid YAML: "
                         f"{str(e).splitlines()[0]}") from None


# ---------------------------------------------------------------------------- schema, version
def file_schema(h5_root):
    """The /meta `schema` attribute of an open file or group ("" when there is none)."""
    if "meta" not in h5_root:
        return ""
    return decode_text(h5_root["meta"].attrs.get("schema", ""))


def check_filetype_version(h5_root, expected_schema, expected_version, source="file"):
    """Raise ValueError unless <h5_root>/meta names `expected_schema` ("hexdyn-result/2") in
    one of the versions `expected_version` (an int or a tuple of the versions accepted), with
    a `schema_version` that agrees; returns the version.

    `h5_root` is an open h5py File or Group; `source` names it in messages.
    """
    accepted = expected_version if isinstance(expected_version, tuple) else (expected_version,)
    base = expected_schema.rsplit("/", 1)[0]
    names = [f"{base}/{v}" for v in accepted]
    if "meta" not in h5_root:
        raise ValueError(f"{source}: not a {expected_schema} file (no /meta group)")
    attrs = h5_root["meta"].attrs
    if "schema" not in attrs:
        raise ValueError(f"{source}: not a {expected_schema} file (/meta has no 'schema')")
    schema = decode_text(attrs["schema"])
    if schema not in names:
        raise ValueError(f"{source}: file schema is {schema!r}, expected "
                         f"{' or '.join(repr(n) for n in names)}")
    if "schema_version" not in attrs:
        raise ValueError(f"{source}: /meta has no 'schema_version' (expected "
                         f"{schema.rsplit('/', 1)[1]})")
    version = attrs["schema_version"]
    try:
        version = int(np.asarray(version).item())
    except (TypeError, ValueError):
        raise ValueError(f"{source}: /meta schema_version {version!r} is not an integer")
    if f"{base}/{version}" != schema:
        raise ValueError(f"{source}: /meta schema_version is {version}, but schema is "
                         f"{schema!r}")
    return version


# ---------------------------------------------------------------------------- checks at open
# Every dataset the schema declares is checked against its declaration when a file is
# opened, from h5py's metadata alone (dtype, shape; no data is read): its element type and
# its shape, each size symbol ("T", "N", "W", ...) fixed by the first dataset that has it
# (/time for T, /scenarios/id for N, the axes of an envelope). A dataset declared for every
# file must be there; others may be absent. A mismatch raises hexdyn.IoError with one line
# naming the file, the dataset, what was found and what was expected.

def element_of(dtype):
    """The schema's element name of an h5py dtype ("float64", "int8", "string", ...)."""
    if h5py.check_string_dtype(dtype) is not None:
        return "string"
    kinds = {"f": "float", "i": "int", "u": "uint"}
    if dtype.kind in kinds and dtype.fields is None:
        return f"{kinds[dtype.kind]}{8 * dtype.itemsize}"
    return str(dtype)


def shape_text(shape):
    if shape is None:
        return "with no dataspace"
    return "(" + ", ".join(map(str, shape)) + ("," if len(shape) == 1 else "") + ")"


def _check_dataset(source, path, ds, specs, sizes):
    """`ds` (an h5py.Dataset at `path`) against its declarations `specs` (alternatives of
    element type, one shape); `sizes` {symbol: (size, dataset it came from)} is completed with
    the symbols this dataset fixes first."""
    elements = [s.element for s in specs]
    shape = specs[0].shape
    found_element = element_of(ds.dtype)
    found = None if ds.shape is None else tuple(ds.shape)
    expected = tuple(d if isinstance(d, int) else sizes.get(d, (None,))[0] for d in shape)
    if (found_element not in elements or found is None or len(found) != len(shape)
            or any(e is not None and e != n for e, n in zip(expected, found))):
        want = tuple(d if e is None else e for d, e in zip(shape, expected))
        whence = [f"{d} = {sizes[d][0]} from {sizes[d][1]}" for d in shape
                  if isinstance(d, str) and d in sizes]
        raise io_error(f"{source}: dataset {path} is {found_element} {shape_text(found)}, "
                       f"expected {' or '.join(elements)} {shape_text(want)}"
                       + (f" ({', '.join(whence)})" if whence else ""))
    for d, n in zip(shape, found):
        if isinstance(d, str) and d not in sizes:
            sizes[d] = (n, path)


def sizes_from_names(root, names_of_size):
    """{symbol: (size, path)} of the sizes an open file or group `root` fixes by its names
    (`names_of_size` {symbol: path}, hexdyn.schema.SIZE_NAMES): L = the number of
    /model/leg_names, ...; a path absent or not a list of names fixes nothing (its own
    check reports it)."""
    sizes = {}
    for symbol, path in names_of_size.items():
        ds = root.get(path.lstrip("/"))
        if isinstance(ds, h5py.Dataset) and ds.shape is not None and len(ds.shape) == 1:
            sizes[symbol] = (ds.shape[0], path)
    return sizes


def check_datasets(source, datasets, layout, required, sizes, kind):
    """Each dataset of `layout` ({path: [DatasetSpec]}) present in `datasets` ({path:
    h5py.Dataset}) checked, in the layout's order; one of `required` missing raises.
    `sizes` as for _check_dataset; `kind` names the file kind in messages."""
    for path, specs in layout.items():
        if path in datasets:
            _check_dataset(source, path, datasets[path], specs, sizes)
        elif path in required:
            raise io_error(f"{source}: no dataset {path}, which every {kind} file has")


def check_declared(source, group, layout, meta_attributes=()):
    """What the checks at open leave to check_layout: every dataset below `group` declared in
    `layout` (or elsewhere in the schema) with its declared `units` attribute (none for "";
    not checked for a `layout` None), and every attribute of `meta_attributes`
    (AttributeSpecs) on /meta. hexdyn.IoError in one line."""
    for path, ds in (datasets_below(group) if layout is not None else {}).items():
        # A dataset of the kind's layout, or one declared elsewhere in the schema (a
        # declaration list the layout of the readers does not name yet).
        if path not in layout and path not in DECLARED:
            raise io_error(f"{source}: dataset {path} is not declared in the schema")
        declared = {s.units for s in layout.get(path, DECLARED.get(path))}
        if "key" in declared:
            continue  # a sweep axis: the unit of its key
        units = decode_text(ds.attrs["units"]) if "units" in ds.attrs else ""
        if units not in declared:
            raise io_error(f"{source}: dataset {path} has units {units!r}, expected "
                           f"{' or '.join(repr(u) for u in sorted(declared))}")
    missing = [a.name for a in meta_attributes if a.name not in group["meta"].attrs]
    if missing:
        raise io_error(f"{source}: /meta has no attribute {', '.join(missing)}")
