"""The checkpoint's checksum (doc/outputs.md, "Checkpoint"), for tests that change a checkpoint
on purpose and sign it again.

Format 3 writes /checksum as 32 hexadecimal digits: the Fletcher sums of the field lists
(state, run summary, output counts; the first 16 digits, as format 2) and of the rest of
what a restart reads (the last 16). resign() recomputes the rest from the file, so a test
can change the identity or the text files' marks and still get past the checksum to the
checks behind it.
"""
import struct

import h5py
import numpy as np

PRIME = 4294967291
TEXTS = [".his", ".prf", ".evt", ".frg", ".imp", ".gau"]


class Fletcher:
    """Two Fletcher sums over the 16-bit pieces of 64-bit values (spb_checkpoint mix)."""

    def __init__(self):
        self.s1, self.s2 = 1, 0

    def mix(self, bits):
        bits &= 0xFFFFFFFFFFFFFFFF
        for k in range(4):
            self.s1 = (self.s1 + ((bits >> (16 * k)) & 0xFFFF)) % PRIME
            self.s2 = (self.s2 + self.s1) % PRIME

    def int(self, v):
        self.mix(int(v))

    def real(self, x):
        self.mix(struct.unpack("<q", struct.pack("<d", float(x)))[0])

    def reals(self, a):
        self.int(len(a))
        for x in a:
            self.real(x)

    def text(self, b):
        b = b.rstrip(b" ")
        self.int(len(b))
        for c in b:
            self.int(c)

    def hex(self):
        return f"{self.s2:08X}{self.s1:08X}"


def _bytes(v):
    return bytes(v) if not isinstance(v, str) else v.encode()


def rest_sum(h):
    """The rest checksum of an open checkpoint, in the order spb_checkpoint reads it."""
    f = Fletcher()
    ident = h["identity"].attrs
    for name in ("program", "revision", "deck"):
        f.text(_bytes(ident[name]))
    f.real(ident["dt"])
    f.int(ident["cells"])
    if "load_t" in h["identity"]:
        f.reals(h["identity/load_t"][()])
        f.reals(h["identity/load_p"][()])
    n = int(ident["n_profiles"])
    f.int(n)
    if n > 0:
        f.reals(h["identity/profile_times"][()])
    out = h["outputs"].attrs
    for e in TEXTS:
        if "body" + e not in out:
            continue
        f.real(out["body" + e])
        f.int(out["tail_bytes" + e])
        f.text(_bytes(out["tail" + e]))
    return f.hex()


def resign(path):
    """Write the checksum of the checkpoint at path again, its rest recomputed (its fields
    part kept byte for byte: latin-1, so a damaged one, not UTF-8, stays as damaged)."""
    with h5py.File(path, "r+") as h:
        fields = _bytes(h.attrs["checksum"]).decode("latin-1")[:16]
        h.attrs["checksum"] = np.bytes_((fields + rest_sum(h)).encode("latin-1"))


def set_program(path, program, sign=True):
    """Write /identity program of the checkpoint at path (a fixed-length string, as spallbar
    writes it) and, with sign, the checksum that fits it, through one handle."""
    with h5py.File(path, "r+") as h:
        h["identity"].attrs["program"] = np.bytes_(program.encode())
        if sign:
            fields = _bytes(h.attrs["checksum"]).decode("latin-1")[:16]
            h.attrs["checksum"] = np.bytes_((fields + rest_sum(h)).encode("latin-1"))


def checksum_matches(path):
    """Whether the rest part of the stored checksum is what the file holds."""
    with h5py.File(path, "r") as h:
        return _bytes(h.attrs["checksum"]).decode()[16:] == rest_sum(h)
