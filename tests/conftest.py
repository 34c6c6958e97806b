"""Before a session of several workers (make test: pytest -n 2) starts them, compile once what
most of its tests need (harness/warm.py): the FMUs and the in-process kernel.  Each worker
otherwise compiles the kernel itself on a cold cache."""
import pytest


@pytest.hookimpl(tryfirst=True)
def pytest_sessionstart(session):
    config = session.config
    if hasattr(config, "workerinput") or not getattr(config.option, "numprocesses", None):
        return    # a worker, or a session of one process (it compiles as it goes)
    from harness.warm import warm_up
    line = warm_up()
    reporter = config.pluginmanager.get_plugin("terminalreporter")
    if reporter is not None:
        reporter.write_line(line)
