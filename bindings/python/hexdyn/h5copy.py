"""A copy of a result read from a file, written as a file of its own (Result.write of a read
result; docs/user/faults.md#pythons-writer): the objects of the file, or of a sweep's kept
run, copied with h5py into an image built in memory and published atomically
(hexdyn.atomic_file).
"""

import os
import secrets

import h5py

from .atomic_file import output_error, publish_atomically, why_not_replaceable
from .h5files import file_identity


def listed_inputs(meta):
    """The absolute paths /meta input_sha256 lists ("SHA256  PATH" per line)."""
    paths = []
    for line in str(meta.get("input_sha256", "") or "").splitlines():
        parts = line.split(None, 1)
        if len(parts) == 2:
            paths.append(parts[1])
    return paths


def _check_copy_target(name, source, inputs):
    """The checks of `hexdyn run -o` on an output path, against the file a result was read
    from (`source`, by identity and path) and the files its /meta lists: hexdyn.IoError. An
    existing `name` must be a regular file (a link, a folder or a special file is refused, not
    followed: atomic_file.why_not_replaceable)."""
    if not name:
        raise output_error(name, "empty path")
    folder = os.path.dirname(os.path.abspath(name))
    if not os.path.isdir(folder):
        raise output_error(name, f"folder '{folder}' does not exist")
    why = why_not_replaceable(name)
    if why:
        raise output_error(name, f"it {why}")
    try:
        target = os.stat(name)
    except FileNotFoundError:
        return
    except OSError as e:
        raise output_error(name, e.strerror) from None
    for role, p in [("file the result was read from", source)] + [
            ("input file", p) for p in inputs]:
        try:
            st = os.stat(p)
        except OSError:
            continue
        if (st.st_dev, st.st_ino) == (target.st_dev, target.st_ino):
            raise output_error(name, f"it is the {role} '{p}' (same device and inode), which "
                               "the output would destroy")


def _copy_attributes(src, dst):
    """The attributes of `src` on `dst` with their stored type and shape, but the dimension
    scale references (attached again by _attach_scales)."""
    for key in src.attrs:
        if key in ("DIMENSION_LIST", "REFERENCE_LIST"):
            continue
        aid = src.attrs.get_id(key)
        dst.attrs.create(key, src.attrs[key], shape=aid.shape, dtype=aid.dtype)


def _attach_scales(src_root, dst_root):
    """Each dataset below `dst_root` attached to the dimension scales its original below
    `src_root` is attached to (DIMENSION_LIST), at the same relative paths."""
    prefix = src_root.name.rstrip("/") + "/"

    def visit(name, obj):
        if not isinstance(obj, h5py.Dataset) or "DIMENSION_LIST" not in obj.attrs:
            return
        for k, refs in enumerate(obj.attrs["DIMENSION_LIST"]):
            for ref in refs:
                scale = src_root.file[ref].name
                if not scale.startswith(prefix):
                    raise ValueError(f"dimension scale {scale} of {obj.name} lies outside "
                                     f"{src_root.name}")
                dst_root[name].dims[k].attach_scale(dst_root[scale[len(prefix):]])
    src_root.visititems(visit)


def _copy_image(file, group, check):
    """The bytes of an HDF5 file holding the objects of the group `group` of the file `file`,
    built in memory (h5py's core driver, no backing store): every member copied with h5py
    (H5Ocopy: values, type, shape, storage), every attribute with its stored type, the
    dimension scales attached again. check() is called before each member of the group is
    copied and after the last (atomic_file: it stops the copy once a signal came)."""
    with h5py.File(file, "r") as src:
        root = src[group]
        with h5py.File(f"hexdyn-copy-{secrets.token_hex(8)}.h5", "w", driver="core",
                       backing_store=False, libver=src.libver) as dst:
            for key in root:
                check()
                root.copy(root[key], dst, name=key, without_attrs=True)
            _copy_attributes(root, dst)
            root.visititems(lambda n, obj: _copy_attributes(obj, dst[n]))
            _attach_scales(root, dst)
            check()
            dst.flush()
            return dst.id.get_file_image()


def write_copy(origin, path, inputs=()):
    """Writes the objects of the group `group` of the file `file` (origin: (file, group,
    identity when read)) as the file `path`: the file's image built in memory (_copy_image)
    and published with atomic_file.publish_atomically (a temporary file beside `path`, written
    with write(2), synced and renamed over `path` when complete; removed on any error or
    signal, an existing file at `path` kept). Refuses, with hexdyn.IoError in one line, a
    source changed since it was read and a target that is the source or one of `inputs`
    (_check_copy_target)."""
    file, group, identity = origin
    name = os.fsdecode(path)
    _check_copy_target(name, file, inputs)
    try:
        unchanged = file_identity(file) == identity
    except OSError as e:
        raise output_error(name, f"the file the result was read from, '{file}', cannot be "
                           f"read: {e.strerror}") from None
    if not unchanged:
        raise output_error(name, f"the file the result was read from, '{file}', changed since "
                           "it was read; open it again")
    publish_atomically(path, lambda check: _copy_image(file, group, check))
