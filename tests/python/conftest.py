"""The marker release_only(why): a test whose code paths the sanitized run (./run.sh test, UDM1_SANITIZED=1)
already exercises in smaller cases, such as a statistical check of an estimator over many seeds, a repeat
at other parameters or a second load of a large scene. It runs in the release suite and is skipped, with its
reason, against the sanitized tools."""

import os

import pytest


def pytest_configure(config):
    config.addinivalue_line("markers", "release_only(why): skipped against the sanitized tools (UDM1_SANITIZED=1)")


def pytest_collection_modifyitems(config, items):
    if not os.environ.get("UDM1_SANITIZED"):
        return
    for item in items:
        mark = item.get_closest_marker("release_only")
        if mark:
            item.add_marker(pytest.mark.skip(reason="release suite only: " + (mark.args[0] if mark.args else "")))
