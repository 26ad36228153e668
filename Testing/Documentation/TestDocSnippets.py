"""Every code block a user would copy from README.md, docs/user-guide.md, docs/mpi.md, docs/operator.md and docs/fields.md runs.

    python3 TestDocSnippets.py --source-dir SRC --build-dir BUILD --python PY
        --pvpython PVPYTHON --pvbatch PVBATCH --mpiexec MPIEXEC --plugin SO
        --package-dir DIR --cmake CMAKE --generator GEN --work-dir WORK

The blocks are run as a user would run them from the root of a clone with a
build in build/: in WORK, where Data/ and build/ are links to the clone's
Data/ and to the build directory.

* ```python blocks that use ParaView run in pvpython; those whose first line
  is a comment naming pvbatch run under `mpiexec -n 2 pvbatch --mpi`; the
  others in VTK Python (Debian's python3, PYTHONPATH from the environment).
  The pvpython blocks of a page run in order in one interpreter, and so do
  its VTK Python blocks (later blocks may use names from earlier ones).
* ```cpp blocks are built against the installed package (--package-dir, the
  MeshProjectionConfig.cmake of `cmake --install`) with the page's ```cmake
  block that calls find_package(MeshProjection) as their CMakeLists.txt, and
  run when they have a main().
* A block preceded by the line `<!-- not-run -->` is skipped (use sparingly).
  Other languages (sh, cmake on its own) are not run.

It also checks that every relative link and image of README.md and docs/*.md
names a file, and a heading, that exist.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

PAGES = ["README.md", "docs/user-guide.md", "docs/mpi.md", "docs/operator.md", "docs/fields.md"]
NOT_RUN = "<!-- not-run -->"


def blocks_of(path):
    """(line, language, code, skipped) of every fenced block of a Markdown file."""
    lines = open(path, encoding="utf-8").read().split("\n")
    out = []
    i = 0
    while i < len(lines):
        m = re.match(r"^```(\w*)\s*$", lines[i])
        if not m:
            i += 1
            continue
        start, language = i, m.group(1)
        j = i + 1
        while j < len(lines) and lines[j].rstrip() != "```":
            j += 1
        if j == len(lines):
            raise SystemExit("%s:%d: unclosed code block" % (path, start + 1))
        k = start - 1
        while k >= 0 and not lines[k].strip():
            k -= 1
        skipped = k >= 0 and lines[k].strip() == NOT_RUN
        out.append((start + 1, language, "\n".join(lines[start + 1:j]) + "\n", skipped))
        i = j + 1
    return out


def slug(heading):
    """GitHub's anchor of a Markdown heading."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def check_links(source_dir, failures):
    """Relative links and images of README.md and docs/*.md name files (and headings) that exist."""
    pages = ["README.md"] + ["docs/" + f for f in sorted(os.listdir(os.path.join(source_dir, "docs")))
                             if f.endswith(".md")]
    anchors = {}
    for page in pages:
        text = open(os.path.join(source_dir, page), encoding="utf-8").read()
        text = re.sub(r"```.*?```", "", text, flags=re.S)
        anchors[page] = {slug(h) for h in re.findall(r"^#+\s+(.*)$", text, re.M)}
    checked = 0
    for page in pages:
        text = open(os.path.join(source_dir, page), encoding="utf-8").read()
        text = re.sub(r"```.*?```", "", text, flags=re.S)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"^[a-z]+:", target):
                continue
            path, _, anchor = target.partition("#")
            resolved = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            checked += 1
            if not os.path.exists(os.path.join(source_dir, resolved)):
                failures.append("%s: link to %s: no such file" % (page, target))
            elif anchor and resolved in anchors and anchor not in anchors[resolved]:
                failures.append("%s: link to %s: no such heading" % (page, target))
    print("links checked: %d" % checked)


def kind_of(code):
    first = code.lstrip().split("\n", 1)[0]
    if first.startswith("#") and "pvbatch" in first:
        return "pvbatch"
    if "paraview" in code:
        return "pvpython"
    return "python"


RUNNER = r'''
import json, sys, traceback
blocks = json.load(open(sys.argv[1]))
scope = {"__name__": "__main__"}
for where, code in blocks:
    print("=== running " + where, flush=True)
    try:
        exec(compile(code, where, "exec"), scope)
    except SystemExit as e:
        if e.code not in (None, 0):
            print("FAILED: " + where + " exited with " + str(e.code), flush=True)
            sys.exit(1)
    except BaseException:
        traceback.print_exc()
        print("FAILED: " + where, flush=True)
        sys.stdout.flush()
        sys.exit(1)
    print("=== ok " + where, flush=True)
'''


def run(command, cwd, what, failures, timeout=600):
    print("$ " + " ".join(command), flush=True)
    try:
        done = subprocess.run(command, cwd=cwd, timeout=timeout, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, universal_newlines=True)
    except subprocess.TimeoutExpired:
        failures.append(what + ": timed out")
        return False
    print(done.stdout, flush=True)
    if done.returncode != 0:
        failures.append("%s: exit code %d" % (what, done.returncode))
        return False
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    for name in ["source-dir", "build-dir", "python", "pvpython", "pvbatch", "mpiexec", "plugin",
                 "package-dir", "cmake", "generator", "work-dir"]:
        parser.add_argument("--" + name, required=True)
    args = parser.parse_args()

    work = os.path.abspath(args.work_dir)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    os.symlink(os.path.join(args.source_dir, "Data"), os.path.join(work, "Data"))
    os.symlink(os.path.abspath(args.build_dir), os.path.join(work, "build"))
    documented = os.path.join(work, "build", "lib", "paraview-5.11", "plugins", "MeshProjection",
                              "MeshProjection.so")
    if not os.path.samefile(documented, args.plugin):
        raise SystemExit("the plugin is not where the documentation says (%s): %s"
                         % (documented, args.plugin))

    failures = []
    check_links(args.source_dir, failures)
    counts = {"python": 0, "pvpython": 0, "pvbatch": 0, "cpp": 0, "skipped": 0}
    for page in PAGES:
        path = os.path.join(args.source_dir, page)
        blocks = blocks_of(path)
        groups = {"python": [], "pvpython": []}
        cmake_lists = [code for (_, language, code, _) in blocks
                       if language == "cmake" and "find_package(MeshProjection" in code]
        for line, language, code, skipped in blocks:
            where = "%s:%d" % (page, line)
            if language not in ("python", "cpp"):
                continue
            if skipped:
                counts["skipped"] += 1
                print("--- not run (marked): " + where)
                continue
            if language == "python":
                kind = kind_of(code)
                counts[kind] += 1
                if kind == "pvbatch":
                    script = os.path.join(work, "pvbatch-%s-%d.py" % (os.path.basename(page), line))
                    open(script, "w").write(code)
                    run([args.mpiexec, "--allow-run-as-root", "--oversubscribe", "-n", "2",
                         args.pvbatch, "--mpi", script], work, where, failures)
                else:
                    groups[kind].append((where, code))
                continue
            # C++: a project of its own, built against the installed package.
            counts["cpp"] += 1
            project = os.path.join(work, "cpp-%s-%d" % (os.path.basename(page), line))
            os.makedirs(project)
            has_main = re.search(r"\bint\s+main\s*\(", code) is not None
            if cmake_lists:
                lists = cmake_lists[0]
            else:
                lists = ("cmake_minimum_required(VERSION 3.16)\nproject(app C CXX)\n"
                         "find_package(MeshProjection REQUIRED)\n"
                         "add_executable(app main.cxx)\n"
                         "target_link_libraries(app PRIVATE MeshProjection::Filters)\n"
                         "vtk_module_autoinit(TARGETS app MODULES MeshProjection::Filters)\n")
            if not has_main:
                # A fragment: compiled, not linked or run.
                lists = re.sub(r"add_executable\((\w+)", r"add_library(\1 OBJECT", lists)
            open(os.path.join(project, "CMakeLists.txt"), "w").write(lists)
            open(os.path.join(project, "main.cxx"), "w").write(code)
            binary = os.path.join(project, "build")
            ok = run([args.cmake, "-S", project, "-B", binary, "-G", args.generator,
                      "-DCMAKE_BUILD_TYPE=Release", "-DMeshProjection_DIR=" + args.package_dir],
                     work, where + " (configure)", failures)
            ok = ok and run([args.cmake, "--build", binary], work, where + " (build)", failures,
                            timeout=900)
            if ok and has_main:
                target = re.search(r"add_executable\((\w+)", lists).group(1)
                run([os.path.join(binary, target)], work, where + " (run)", failures)
        for kind, interpreter in (("python", args.python), ("pvpython", args.pvpython)):
            if not groups[kind]:
                continue
            listing = os.path.join(work, "%s-%s.json" % (kind, os.path.basename(page)))
            json.dump(groups[kind], open(listing, "w"))
            runner = os.path.join(work, "runner.py")
            open(runner, "w").write(RUNNER)
            run([interpreter, runner, listing], work, "%s blocks of %s" % (kind, page), failures)

    print("blocks: %s" % counts)
    if counts["python"] == 0 or counts["pvpython"] == 0 or counts["cpp"] == 0:
        failures.append("expected VTK Python, pvpython and C++ blocks, found %s" % counts)
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    print("all documentation snippets ran")
    return 0


if __name__ == "__main__":
    sys.exit(main())
