"""Which tests run where in ./run.sh test, which runs the tools' and the package's tests twice over: once in CTest's
release run and once against the sanitized tools or the sanitized library (ASan, LSan, UBSan).

- The marker release_only(why): a test whose code paths the sanitized run (UDM1_SANITIZED=1) already exercises
  in smaller cases, such as a statistical check of an estimator over many seeds, a repeat at other parameters or
  a second load of a large scene. It runs in the release run and is skipped, with its reason, against the
  sanitized tools or library.
- UDM1_SANITIZED_LATER=file,file,...: the release run of ./run.sh test names the test files that run again, whole,
  against the sanitized tools or library; in the release run only their release_only tests run (the rest are
  skipped, with that reason), so that every test runs once, where it checks most. A plain ctest (no variable) runs
  everything."""

import os

import pytest


def pytest_configure(config):
    config.addinivalue_line("markers", "release_only(why): skipped against the sanitized tools or library (UDM1_SANITIZED=1)")


def pytest_collection_modifyitems(config, items):
    later = {f for f in os.environ.get("UDM1_SANITIZED_LATER", "").split(",") if f}
    for item in items:
        mark = item.get_closest_marker("release_only")
        if os.environ.get("UDM1_SANITIZED") and mark:
            item.add_marker(pytest.mark.skip(reason="release suite only: " + (mark.args[0] if mark.args else "")))
        elif not os.environ.get("UDM1_SANITIZED") and not mark and item.path.name in later:
            item.add_marker(pytest.mark.skip(reason="runs against the sanitized tools below (UDM1_SANITIZED_LATER)"))
