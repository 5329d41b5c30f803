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
