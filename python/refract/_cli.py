"""The `refract` command of a pip-installed package: runs the executable installed beside
the package (refract/bin/refract) with the same arguments."""
import os
import sys


def main():
    exe = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "refract")
    if not os.access(exe, os.X_OK):
        sys.stderr.write("refract: the executable " + exe + " is missing (reinstall the package)\n")
        return 2
    module = os.path.join(os.path.dirname(exe), "..", "librefract_image_io.so")  # the package's image module
    if not os.environ.get("REFRACT_IMAGE_IO") and os.path.exists(module):
        os.environ["REFRACT_IMAGE_IO"] = os.path.normpath(module)
    os.execv(exe, ["refract"] + sys.argv[1:])
    return 2  # not reached


if __name__ == "__main__":
    sys.exit(main())
