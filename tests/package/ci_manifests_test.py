#!/usr/bin/env python3
# The docs_ci_manifests test: the GitHub Actions matrix and the Kubernetes Jobs in
# docs/user-guide.md ("Sharded builds") are valid YAML, and their shard arithmetic holds:
# every shard 1..N built once with --shard I/N, the merge after all of them over all of them.
import re
import sys

import yaml

text = open(sys.argv[1], encoding="utf-8").read()
section = text[text.index("## Sharded builds"):text.index("## Loops, switches and unrolling")]
blocks = re.findall(r"```yaml\n(.*?)```", section, re.S)
if len(blocks) != 2:
    sys.exit(f"expected 2 yaml blocks in the section, found {len(blocks)}")

# GitHub Actions: a matrix of 1..N, each building shard I/N into shard-I; merge needs it.
actions = yaml.safe_load(blocks[0])
shard, merge = actions["jobs"]["shard"], actions["jobs"]["merge"]
indices = shard["strategy"]["matrix"]["shard"]
n = len(indices)
assert indices == list(range(1, n + 1)), indices
runs = [s["run"] for s in shard["steps"] if "run" in s]
build = [r for r in runs if " build " in r]
assert len(build) == 1 and f"--shard ${{{{ matrix.shard }}}}/{n}" in build[0], build
assert merge["needs"] == "shard", merge["needs"]
assert any("watergen merge" in s.get("run", "") for s in merge["steps"]), merge["steps"]

# Kubernetes: an Indexed Job of N completions whose pod I builds shard I+1 of N, then a Job
# that merges the shard directories it wrote.
shards, merger = list(yaml.safe_load_all(blocks[1]))
spec = shards["spec"]
assert shards["kind"] == "Job" and spec["completionMode"] == "Indexed", spec
assert spec["completions"] == spec["parallelism"] == n, (spec["completions"], n)
command = " ".join(spec["template"]["spec"]["containers"][0]["command"])
assert f"--shard $((JOB_COMPLETION_INDEX + 1))/{n}" in command, command
assert "--out /shards/shard-$((JOB_COMPLETION_INDEX + 1))" in command, command
merge_command = " ".join(merger["spec"]["template"]["spec"]["containers"][0]["command"])
assert "watergen merge" in merge_command and "/shards/shard-*" in merge_command, merge_command
assert merger["spec"]["template"]["spec"]["restartPolicy"] == "Never"
print(f"both manifests parse: {n} shards, each once, merged after all")
