"""Shared checks of the command-line tools' tests."""


def fails_cleanly(run, args, words, folder, code=None):
    """run(*args, cwd=folder) must fail (with `code` if given) with one line on stderr holding `words`,
    and leave no new file (not even a temporary one) in folder."""
    before = set(folder.iterdir())
    r = run(*args, cwd=folder)
    lines = r.stderr.strip().splitlines()
    assert r.returncode != 0 and (code is None or r.returncode == code), (args, r.returncode, r.stderr)
    assert len(lines) == 1 and words in lines[0], (args, words, r.stderr)
    assert set(folder.iterdir()) == before, args
    return r


EXR_COMPRESSIONS = {0: "none", 3: "zip"}  # OpenEXR's compression attribute: the values the tools write


def exr_compression(path):
    """The compression an OpenEXR file's header names ("none", "zip", or its number), from the header's
    attributes (name, type, size, value) after the magic number and version."""
    data = path.read_bytes()
    assert data[:4] == b"\x76\x2f\x31\x01", path
    at = 8
    while data[at] != 0:
        name_end = data.index(b"\0", at)
        type_end = data.index(b"\0", name_end + 1)
        size = int.from_bytes(data[type_end + 1:type_end + 5], "little")
        if data[at:name_end] == b"compression":
            value = data[type_end + 5]
            return EXR_COMPRESSIONS.get(value, value)
        at = type_end + 5 + size
    raise AssertionError(f"{path}: no compression attribute")
