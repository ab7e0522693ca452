#!/usr/bin/env python3
"""cluster.DeployFiles: the files under deploy/ checked where no registry,
container engine or Kubernetes cluster is at hand (the Slurm script runs for
real in cluster.SlurmArrayDataset).

- The container's build stage installs bootstrap.sh's PACKAGES (one list);
  its run stage installs packages that exist in Debian bookworm (they are
  installed here, pulled in by bootstrap.sh) and that hold every library the
  built `facial` links.
- The entry point picks lavapipe, or NVIDIA's ICD first where /dev/nvidia*
  exists, and leaves a driver list given by the user alone.
- The Kubernetes manifest's shard count equals its completions; its pods and
  merge share one volume and one output folder.
- Every shell script is shellcheck-clean.

Usage: deploy_files_test.py SOURCE_DIR FACIAL_PROGRAM [unittest options]
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import yaml

SOURCE_DIR = ""
FACIAL = ""


def read(relative):
    with open(os.path.join(SOURCE_DIR, relative), encoding="utf-8") as f:
        return f.read()


def container_stages():
    """The Containerfile's instructions, one list per stage (FROM starts one);
    continuation lines joined, comments dropped."""
    text = re.sub(r"\\\n", " ", read("deploy/container/Containerfile"))
    stages = []
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if line.startswith("FROM "):
            stages.append([])
        stages[-1].append(line)
    return stages


def apt_installs(stage):
    """Packages named by `apt-get install` in a stage's RUN instructions."""
    packages = []
    for line in stage:
        for command in re.split(r"&&|;", line):
            words = command.split()
            if "apt-get" in words and "install" in words:
                after = words[words.index("install") + 1:]
                packages += [w for w in after if not w.startswith("-")]
    return packages


def resolved_libraries(program):
    """soname -> path of each shared library `program` names (its NEEDED
    entries), as ldd resolves them."""
    dynamic = subprocess.run(["readelf", "-d", program], capture_output=True, text=True, check=True).stdout
    needed = re.findall(r"\(NEEDED\)\s+Shared library: \[(.+?)\]", dynamic)
    listing = subprocess.run(["ldd", program], capture_output=True, text=True, check=True).stdout
    resolved = dict(re.findall(r"^\s*(\S+) => (/\S+)", listing, re.M))
    # The dynamic loader is listed by its path alone.
    resolved.update({os.path.basename(p): p for p in re.findall(r"^\s*(/\S+) \(", listing, re.M)})
    unresolved = [soname for soname in needed if soname not in resolved]
    if unresolved:
        raise AssertionError(f"{program}: ldd does not resolve {', '.join(unresolved)}")
    return {soname: resolved[soname] for soname in needed}


def linked_packages(program):
    """soname -> the Debian package holding it, for each library `program` names."""
    # With merged /usr, dpkg knows either a library's path or its link target: ask for both, at once.
    paths = {soname: (path, os.path.realpath(path)) for soname, path in resolved_libraries(program).items()}
    found = subprocess.run(["dpkg", "-S", *{p for pair in paths.values() for p in pair}],
                           capture_output=True, text=True).stdout
    owners = {path: owner.split(":")[0] for owner, path in re.findall(r"^(\S+): (/\S+)$", found, re.M)}
    packages = {}
    for soname, (path, target) in paths.items():
        owner = owners.get(path) or owners.get(target)
        if owner is None:
            raise AssertionError(f"{program} links {path}, which no Debian package holds")
        packages[soname] = owner
    return packages


class Container(unittest.TestCase):
    def test_build_stage_installs_bootstraps_packages_only(self):
        build = container_stages()[0]
        self.assertIn("COPY bootstrap.sh ./", build)
        self.assertIn("RUN ./bootstrap.sh deps", build)
        self.assertEqual(apt_installs(build), [], "the build stage installs packages of its own")
        out = subprocess.run([os.path.join(SOURCE_DIR, "bootstrap.sh"), "no-such-mode"],
                             capture_output=True, text=True)
        self.assertIn("deps", out.stderr, "bootstrap.sh has no 'deps' mode")

    def test_run_stage_packages_exist_in_bookworm(self):
        for package in apt_installs(container_stages()[-1]):
            status = subprocess.run(["dpkg-query", "-W", "-f=${Status}", package],
                                    capture_output=True, text=True).stdout
            self.assertEqual(status, "install ok installed",
                             f"Containerfile: {package} is not installed here (misspelt, or another "
                             f"Debian release's name?)")

    def test_run_stage_holds_every_library_facial_links(self):
        installed = set(apt_installs(container_stages()[-1]))
        for soname, package in linked_packages(FACIAL).items():
            self.assertTrue(package in installed,
                            f"Containerfile: facial links {soname} from {package}, which the image lacks")


class Entrypoint(unittest.TestCase):
    """The entry point in a fake root (FACIAL_ICD_ROOT), with a stand-in
    `facial` that prints the driver list it was given."""

    def setUp(self):
        self.root = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.root)
        self.bin = os.path.join(self.root, "bin")
        os.makedirs(self.bin)
        with open(os.path.join(self.bin, "facial"), "w") as f:
            f.write('#!/bin/sh\necho "$VK_ICD_FILENAMES|$VK_DRIVER_FILES|$*"\n')
        os.chmod(os.path.join(self.bin, "facial"), 0o755)
        self.lavapipe = self.touch("usr/share/vulkan/icd.d/lvp_icd.x86_64.json")

    def touch(self, relative):
        path = os.path.join(self.root, relative)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        open(path, "w").close()
        return path

    def run_entrypoint(self, **env):
        environment = {k: v for k, v in os.environ.items() if k not in ("VK_ICD_FILENAMES", "VK_DRIVER_FILES")}
        environment.update(FACIAL_ICD_ROOT=self.root, PATH=self.bin + ":" + os.environ["PATH"], **env)
        result = subprocess.run([os.path.join(SOURCE_DIR, "deploy/container/entrypoint.sh"), "info", "x.glb"],
                                capture_output=True, text=True, env=environment)
        self.assertEqual(result.returncode, 0, result.stderr)
        drivers, newer, args = result.stdout.strip().split("|")
        self.assertEqual(args, "info x.glb")
        self.assertEqual(drivers, newer)
        return drivers

    def test_cpu_node_gets_lavapipe(self):
        self.assertEqual(self.run_entrypoint(), self.lavapipe)

    def test_gpu_node_gets_the_mounted_nvidia_icd_first(self):
        self.touch("dev/nvidia0")
        nvidia = self.touch("etc/vulkan/icd.d/nvidia_icd.json")
        self.assertEqual(self.run_entrypoint(), nvidia + ":" + self.lavapipe)

    def test_gpu_node_without_a_mounted_icd_gets_the_images_own(self):
        self.touch("dev/nvidia0")
        own = self.touch("opt/facial/nvidia_icd.json")
        self.assertEqual(self.run_entrypoint(), own + ":" + self.lavapipe)

    def test_users_driver_list_wins(self):
        self.touch("dev/nvidia0")
        self.touch("etc/vulkan/icd.d/nvidia_icd.json")
        self.assertEqual(self.run_entrypoint(VK_ICD_FILENAMES="/mine.json", VK_DRIVER_FILES="/mine.json"),
                         "/mine.json")

    def test_no_driver_is_one_line(self):
        os.remove(self.lavapipe)
        result = subprocess.run([os.path.join(SOURCE_DIR, "deploy/container/entrypoint.sh")],
                                capture_output=True, text=True,
                                env={"FACIAL_ICD_ROOT": self.root, "PATH": self.bin + ":/usr/bin:/bin"})
        self.assertEqual(result.returncode, 1)
        self.assertEqual(len(result.stderr.strip().splitlines()), 1, result.stderr)
        self.assertIn("no Vulkan driver", result.stderr)


class Kubernetes(unittest.TestCase):
    def setUp(self):
        documents = list(yaml.safe_load_all(read("deploy/kubernetes/dataset-indexed-job.yaml")))
        self.by_name = {(d["kind"], d["metadata"]["name"]): d for d in documents}
        self.shards = self.by_name[("Job", "facial-dataset")]
        self.merge = self.by_name[("Job", "facial-dataset-merge")]

    @staticmethod
    def container(job):
        return job["spec"]["template"]["spec"]["containers"][0]

    def test_indexed_job_shard_count_equals_completions(self):
        spec = self.shards["spec"]
        self.assertEqual(spec["completionMode"], "Indexed")
        env = {e["name"]: e.get("value") for e in self.container(self.shards)["env"]}
        self.assertEqual(int(env["FACIAL_SHARD_COUNT"]), spec["completions"])
        self.assertLessEqual(spec["parallelism"], spec["completions"])

    def test_shards_and_merge_share_one_volume_and_folder(self):
        claims = set()
        for job in (self.shards, self.merge):
            volumes = {v["name"]: v for v in job["spec"]["template"]["spec"]["volumes"]}
            mounts = {m["mountPath"]: m["name"] for m in self.container(job)["volumeMounts"]}
            claims.add(volumes[mounts["/data"]]["persistentVolumeClaim"]["claimName"])
            self.assertIn("--out /data/dataset", " ".join(self.container(job)["args"]))
        self.assertEqual(claims, {"facial-dataset"})
        claim = self.by_name[("PersistentVolumeClaim", "facial-dataset")]
        self.assertIn("ReadWriteMany", claim["spec"]["accessModes"])
        self.assertIn("dataset merge", " ".join(self.container(self.merge)["args"]))


class Scripts(unittest.TestCase):
    def test_slurm_script_is_an_array_job(self):
        self.assertRegex(read("deploy/slurm/dataset-array.sbatch"), r"(?m)^#SBATCH --array=0-\d+$")

    def test_shell_scripts_are_shellcheck_clean(self):
        scripts = ["deploy/container/entrypoint.sh", "deploy/slurm/dataset-array.sbatch",
                   "tests/cluster/slurm_array_test.sh"]
        result = subprocess.run(["shellcheck", *scripts], cwd=SOURCE_DIR, capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: deploy_files_test.py SOURCE_DIR FACIAL_PROGRAM [unittest options]")
    SOURCE_DIR, FACIAL = sys.argv[1], sys.argv[2]
    unittest.main(argv=[sys.argv[0], *sys.argv[3:]], verbosity=2)
