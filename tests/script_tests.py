"""The runner of the Python test scripts (tests/test_*.py): every test_* function of the
script, in the order written, on one temporary folder (a later test may read an earlier one's
files), with the tirefe binary given on the command line as the script's TIREFE. Every failure
is reported, then the next test runs; the folder is kept when one failed.
"""
import os
import shutil
import sys
import tempfile
import traceback


def run(namespace, prefix):
    """Runs the test_* functions of 'namespace' (a script's globals()) and exits."""
    if len(sys.argv) != 2:
        sys.exit(namespace["__doc__"])
    namespace["TIREFE"] = os.path.abspath(sys.argv[1])
    folder = tempfile.mkdtemp(prefix=prefix)
    tests = [value for name, value in namespace.items() if name.startswith("test_")]
    failed = 0
    for test in tests:
        try:
            test(folder)
            print(f"passed: {test.__name__}")
        except Exception:  # report every failure, then go on
            failed += 1
            print(f"FAILED: {test.__name__}\n{traceback.format_exc()}")
    print(f"{len(tests) - failed} passed, {failed} failed")
    if failed:
        print(f"(files kept in {folder})")
    else:
        shutil.rmtree(folder)
    sys.exit(1 if failed else 0)
