"""pip's build of refract: configures and builds the CMake project, then packages the
native module, the image module, the `refract` executable and python/refract/.

A plain setuptools build (setuptools and wheel are Debian packages, python3-setuptools and
python3-wheel) so that `pip install --no-build-isolation .` works offline against the
system's packages; scikit-build-core would do the same but is not packaged by Debian 12.
REFRACT_CMAKE_ARGS adds CMake options (e.g. -DCMAKE_CXX_COMPILER_LAUNCHER=ccache);
CMAKE_BUILD_PARALLEL_LEVEL sets the build's jobs as for any CMake build."""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(refract VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    """Builds the targets the package needs in the CMake tree build-pip/ of the checkout."""

    def build_extension(self, ext):
        tree = os.path.join(ROOT, "build-pip")  # kept: a second install rebuilds only what changed
        package = os.path.dirname(os.path.abspath(self.get_ext_fullpath(ext.name)))
        configure = ["cmake", "-S", ROOT, "-B", tree, "-DCMAKE_BUILD_TYPE=Release", "-DREFRACT_BUILD_TESTS=OFF",
                     "-DPython3_EXECUTABLE=" + sys.executable]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        configure += shlex.split(os.environ.get("REFRACT_CMAKE_ARGS", ""))
        subprocess.check_call(configure)
        subprocess.check_call(["cmake", "--build", tree, "--target", "refract_python", "refract_image_io", "refract"])
        os.makedirs(os.path.join(package, "bin"), exist_ok=True)
        native = glob.glob(os.path.join(tree, "python", "refract", "_refract*.so"))
        image_io = glob.glob(os.path.join(tree, "core", "image_io", "librefract_image_io.so"))
        if len(native) != 1 or len(image_io) != 1:
            raise RuntimeError("refract: the CMake build did not produce the Python or the image module")
        shutil.copy2(native[0], self.get_ext_fullpath(ext.name))
        shutil.copy2(image_io[0], os.path.join(package, "librefract_image_io.so"))
        shutil.copy2(os.path.join(tree, "cli", "refract"), os.path.join(package, "bin", "refract"))


setup(
    version=project_version(),
    packages=["refract"],
    package_dir={"refract": "python/refract"},
    package_data={"refract": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("refract._refract", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
