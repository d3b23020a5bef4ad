#!/usr/bin/python3
"""Lists the scenarios finished in a sweep checkpoint: the ids of the intact row records
of every journal in CHECKPOINT_DIR (the layout of src/hexdyn/sweep/journal.hpp, read
here independently of hexdyn: a header of "HXDJRN02" and its size H (uint32 at byte 8;
"HXDJRN01": 64 bytes), then records of magic "HXR1", kind,
index, identity, payload size, payload and a CRC-32 of all but the magic, which is
zlib's). One id per line, sorted; records that fail their checksum are left out.

    journal_rows.py CHECKPOINT_DIR [--damage FILE] [--kind row|crash]
"""
import glob
import os
import struct
import sys
import zlib

MAGIC = b"HXR1"


def header_size(data):
    if data[:8] == b"HXDJRN02" and len(data) >= 12:
        return struct.unpack_from("<I", data, 8)[0]
    return 64


def records(data):
    at = header_size(data)
    while at + 36 <= len(data):
        if data[at:at + 4] != MAGIC:
            at += 1
            continue
        kind, index, ident, size = struct.unpack_from("<IQQQ", data, at + 4)
        end = at + 32 + size
        if end + 4 > len(data):
            at += 1
            continue
        (crc,) = struct.unpack_from("<I", data, end)
        if crc != zlib.crc32(data[at + 4:end]):
            at += 1
            continue
        yield kind, index, at
        at = end + 4


def main():
    directory = sys.argv[1]
    kind = 2 if "--kind" in sys.argv and sys.argv[sys.argv.index("--kind") + 1] == "crash" else 1
    ids = set()
    for path in sorted(glob.glob(os.path.join(directory, "journal-*.hxj"))):
        with open(path, "rb") as f:
            data = f.read()
        for k, index, _ in records(data):
            if k == kind:
                ids.add(index)
    for i in sorted(ids):
        print(f"{i:06d}")


if __name__ == "__main__":
    main()
