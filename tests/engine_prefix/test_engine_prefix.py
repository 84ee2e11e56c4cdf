"""An engine from an install prefix of one's own build (-DIMPACTBENCH_<ENGINE>_PREFIX, adapters/CMakeLists.txt;
docs/for-engine-authors.md), checked by pointing it at Debian's own prefix, /usr: the configure finds the engine
there and says so; a prefix without the engine stops the configure, naming the option, the prefix and what
was found instead; set back to /usr, the engine is found anew (not the failed search's cached result).

    /usr/bin/python3 tests/engine_prefix/test_engine_prefix.py SOURCE_DIR SCRATCH_DIR ENGINE
"""

import os
import shutil
import subprocess
import sys


def configure(source, build, engine, prefix):
    option = f"-DIMPACTBENCH_{engine.upper()}_PREFIX={prefix}"
    return subprocess.run(["cmake", "-S", source, "-B", build, "-G", "Ninja", f"-DIMPACTBENCH_ENGINES={engine}", option,
                           "-DIMPACTBENCH_TESTS=OFF", "-DIMPACTBENCH_BENCH=OFF"], capture_output=True, text=True)


def main():
    source, scratch, engine = sys.argv[1:4]
    shutil.rmtree(scratch, ignore_errors=True)
    build, empty = os.path.join(scratch, "build"), os.path.join(scratch, "empty_prefix")
    os.makedirs(empty)
    option = f"IMPACTBENCH_{engine.upper()}_PREFIX"

    debian = configure(source, build, engine, "/usr")
    assert debian.returncode == 0, debian.stdout + debian.stderr
    assert f"-- {engine}: from {option}=/usr: " in debian.stdout, debian.stdout

    elsewhere = configure(source, build, engine, empty)
    assert elsewhere.returncode != 0, elsewhere.stdout
    said = " ".join(elsewhere.stderr.split())  # CMake wraps its messages
    assert f"{option}={os.path.realpath(empty)}: {engine} was not found there (found: /usr/" in said, elsewhere.stderr

    again = configure(source, build, engine, "/usr")
    assert again.returncode == 0, again.stdout + again.stderr
    assert f"-- {engine}: from {option}=/usr: " in again.stdout, again.stdout
    shutil.rmtree(scratch)
    print(f"test_engine_prefix: {engine} from {option}=/usr, refused from an empty prefix, found anew")


if __name__ == "__main__":
    main()
