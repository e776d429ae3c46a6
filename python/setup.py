# Bundles the MeshLab 2025.07 plugin built by CMake (build/plugins/meshlab2025) into the
# package, so that `pip install ./python` gives a package that can load it anywhere.
import os
import shutil

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
PLUGIN = os.path.join(HERE, "..", "build", "plugins", "meshlab2025", "libfilter_quadsimp.so")


class BuildWithPlugin(build_py):
    def run(self):
        super().run()
        plugin = os.environ.get("QUADSIMP_PLUGIN", PLUGIN)
        if not os.path.exists(plugin):
            raise SystemExit(f"quadsimp-pymeshlab: {plugin} not found; build the plugin first (scripts/build.sh)")
        shutil.copy2(plugin, os.path.join(self.build_lib, "quadsimp_pymeshlab", "libfilter_quadsimp.so"))


setup(cmdclass={"build_py": BuildWithPlugin})
