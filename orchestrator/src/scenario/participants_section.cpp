#include "scenario/participants_section.h"

#include <cmath>

#include "cosim/util/host_memory.h"
#include "scenario/limits.h"

namespace cosim::orchestrator {

namespace fs = std::filesystem;

const std::map<std::string, AdapterInfo>& knownAdapters() {
  static const std::map<std::string, AdapterInfo> m = {
      {"analytic-fluid", {"cosim-analytic-fluid", wire::FLUID}},
      {"openfoam", {"cosimFoam", wire::FLUID}},
      {"free-particles", {"cosim-free-particles", wire::PARTICLES}},
      {"liggghts", {"cosim-liggghts", wire::PARTICLES}},
  };
  return m;
}

const std::vector<KeySpec>& ParticipantSpec::keys() {
  static const std::vector<KeySpec> k = {
      {"adapter", "required",
       "analytic-fluid | openfoam (fluid), free-particles | liggghts (particles), or any name "
       "with command:"},
      {"command", "the adapter's executable", "executable to run (found next to cosim or in PATH)"},
      {"args", "[]", "extra command-line arguments, a list of texts"},
      {"launch", "local",
       "local (cosim starts it here) | mpirun (cosim starts it with mpirun, hostfile:) | slurm "
       "(cosim starts it with srun in your allocation, slurm:) | external (started elsewhere, "
       "connects)"},
      {"mpi", "1", "MPI ranks, a whole number in 1 .. 4096 (> 1: run under mpirun, or srun)"},
      {"slurm", "{}", "launch: slurm: nodes, nodelist, args (docs/cluster.md)"},
      {"hostfile", "none", "launch: mpirun: mpirun's host file, relative to the scenario file"},
      {"workdir", "none",
       "absolute folder on the participant's node when it does not see the run folder: its "
       "files travel over the link (docs/cluster.md)"},
      {"files", "none", "case folder, relative to the scenario file, copied and templated"},
      {"timeout", "300", "seconds one step may take before it counts as hung; > 0, <= 1e6"},
      {"options", "{}", "adapter settings, sent to the adapter as they are"},
  };
  return k;
}

const std::vector<KeySpec>& SlurmLaunch::keys() {
  static const std::vector<KeySpec> k = {
      {"nodes", "0", "srun --nodes: whole number of nodes, 0 = as Slurm places the ranks"},
      {"nodelist", "none", "srun --nodelist, e.g. node[01-04]"},
      {"args", "[]", "further srun options, a list of texts (e.g. --cpus-per-task=2)"},
  };
  return k;
}

namespace {

SlurmLaunch parseSlurm(const YAML::Node& n, const Context& ctx, const std::string& key) {
  if (!n.IsMap()) ctx.fail(n, key, "expected a map with nodes:, nodelist:, args:");
  ctx.allowOnly(n, key, SlurmLaunch::keys());
  SlurmLaunch s;
  if (n["nodes"]) {
    const double v = ctx.number(n["nodes"], key + ".nodes");
    if (v < 0 || v != std::floor(v) || v > 100000)
      ctx.fail(n["nodes"], key + ".nodes", "expected a whole number of nodes >= 0");
    s.nodes = static_cast<int>(v);
  }
  if (n["nodelist"]) s.nodelist = ctx.text(n["nodelist"], key + ".nodelist");
  if (n["args"]) {
    if (!n["args"].IsSequence())
      ctx.fail(n["args"], key + ".args", "expected a list of srun options");
    for (std::size_t i = 0; i < n["args"].size(); ++i) {
      const std::string a = ctx.text(n["args"][i], key + ".args[" + std::to_string(i) + "]");
      if (a.rfind("-", 0) != 0)
        ctx.fail(n["args"][i], key + ".args[" + std::to_string(i) + "]",
                 "expected an srun option starting with '-', got '" + a + "'");
      s.args.push_back(a);
    }
  }
  return s;
}

ParticipantSpec parseParticipant(const std::string& pname, const YAML::Node& p, const Context& ctx,
                                 const fs::path& dir) {
  const std::string key = "participants." + pname;
  if (!p.IsMap()) ctx.fail(p, key, "expected a map with at least 'adapter:'");
  ctx.allowOnly(p, key, ParticipantSpec::keys());
  ParticipantSpec ps;
  ps.name = pname;
  ps.adapter = ctx.text(p["adapter"], key + ".adapter");
  ps.role = pname == "fluid" ? wire::FLUID : wire::PARTICLES;
  auto known = knownAdapters().find(ps.adapter);
  if (p["command"]) {
    ps.command = ctx.text(p["command"], key + ".command");
  } else if (known == knownAdapters().end()) {
    std::string list;
    for (const auto& [k, i] : knownAdapters()) list += (list.empty() ? "" : ", ") + k;
    ctx.fail(p["adapter"], key + ".adapter",
             "unknown adapter '" + ps.adapter + "' (known: " + list +
                 "; a custom adapter also needs 'command: /path/to/executable')");
  } else {
    if (known->second.role != ps.role) {
      ctx.fail(p["adapter"], key + ".adapter",
               "adapter '" + ps.adapter + "' simulates " +
                   (known->second.role == wire::FLUID ? "the fluid" : "particles") +
                   " and cannot be the '" + pname + "' participant");
    }
    ps.command = known->second.executable;
  }
  if (p["args"]) {
    if (!p["args"].IsSequence()) ctx.fail(p["args"], key + ".args", "expected a list of arguments");
    for (std::size_t i = 0; i < p["args"].size(); ++i)
      ps.args.push_back(ctx.text(p["args"][i], key + ".args[" + std::to_string(i) + "]"));
  }
  if (p["launch"]) {
    ps.launch = ctx.text(p["launch"], key + ".launch");
    if (ps.launch != "local" && ps.launch != "external" && ps.launch != "mpirun" &&
        ps.launch != "slurm") {
      ctx.fail(p["launch"], key + ".launch",
               "expected 'local' (cosim starts it here), 'mpirun' (with mpirun and a host file), "
               "'slurm' (with srun in your allocation) or 'external' (started elsewhere, connects "
               "to the orchestrator)");
    }
  }
  if (p["slurm"]) {
    if (ps.launch != "slurm")
      ctx.fail(p["slurm"], key + ".slurm",
               "only used with launch: slurm (launch is " + ps.launch + ")");
    ps.slurm = parseSlurm(p["slurm"], ctx, key + ".slurm");
  }
  if (p["hostfile"]) {
    if (ps.launch != "mpirun")
      ctx.fail(p["hostfile"], key + ".hostfile",
               "only used with launch: mpirun (launch is " + ps.launch + ")");
    ps.hostfile = dir / ctx.text(p["hostfile"], key + ".hostfile");
    if (!fs::is_regular_file(ps.hostfile))
      ctx.fail(p["hostfile"], key + ".hostfile",
               "host file '" + ps.hostfile.string() +
                   "' does not exist (paths are relative to the scenario file)");
  }
  if (p["mpi"]) {
    double n = ctx.number(p["mpi"], key + ".mpi");
    if (n < 1 || n != std::floor(n) || n > 4096) {
      ctx.fail(p["mpi"], key + ".mpi",
               "expected a whole number of MPI ranks >= 1, got " + p["mpi"].Scalar());
    }
    ps.mpi = static_cast<int>(n);
    // Ranks started on this host must fit in its memory: a solver's rank takes at least
    // kRankBytes (LIGGGHTS and OpenFOAM ranks hold 80-90 MB resident at the smallest scenes).
    const bool this_host = ps.launch == "local" || (ps.launch == "mpirun" && !p["hostfile"]);
    const double memory = util::hostMemoryBytes();
    if (this_host && memory > 0 && ps.mpi * limits::kRankBytes > memory)
      ctx.fail(p["mpi"], key + ".mpi",
               std::to_string(ps.mpi) + " MPI ranks on this host need at least " +
                   std::to_string(static_cast<long>(ps.mpi * limits::kRankBytes / 1e9)) +
                   " GB (50 MB a rank) and it has " +
                   std::to_string(static_cast<long>(memory / 1e9)) +
                   " GB: give fewer, or spread them over nodes (launch: slurm, or mpirun with a "
                   "hostfile; docs/cluster.md)");
  }
  if (p["workdir"]) {
    ps.workdir = ctx.text(p["workdir"], key + ".workdir");
    if (!fs::path(ps.workdir).is_absolute())
      ctx.fail(p["workdir"], key + ".workdir",
               "expected an absolute folder on the participant's node, got '" + ps.workdir + "'");
    if (ps.launch == "external")
      ctx.fail(p["workdir"], key + ".workdir",
               "an external participant is given its folder on its own command line "
               "(--workdir DIR); remove workdir: here");
  }
  if (p["timeout"]) {
    ps.timeout = ctx.positive(p["timeout"], key + ".timeout", "(seconds one step may take)");
    ps.timeout = ctx.inRange(p["timeout"], key + ".timeout", 0, limits::kMaxTimeout, "seconds");
  }
  if (p["files"]) {
    ps.files = dir / ctx.text(p["files"], key + ".files");
    if (!fs::is_directory(ps.files)) {
      ctx.fail(p["files"], key + ".files",
               "folder '" + ps.files.string() +
                   "' does not exist (paths are relative to the scenario file)");
    }
  }
  ps.options = p["options"] ? YAML::Clone(p["options"]) : YAML::Node(YAML::NodeType::Map);
  if (!ps.options.IsMap())
    ctx.fail(p["options"], key + ".options", "expected a map of adapter settings");
  return ps;
}

}  // namespace

ParticipantsSection parseParticipants(const YAML::Node& parts, const Context& ctx,
                                      const fs::path& dir) {
  if (!parts || !parts.IsMap() || parts.size() == 0) {
    ctx.failTop("participants",
                "missing; expected at least 'particles: { adapter: ... }' (and 'fluid:' for "
                "coupled scenes)");
  }
  ParticipantsSection out;
  for (const auto& kv : parts) {
    const std::string pname = ctx.keyName(kv.first, "participants");
    if (pname != "fluid" && pname != "particles") {
      ctx.fail(kv.first, "participants." + pname,
               "unknown participant; a scene has 'fluid' and/or 'particles'");
    }
    out[pname] = parseParticipant(pname, kv.second, ctx, dir);
  }
  if (!out.count("particles")) {
    ctx.failTop("participants.particles",
                "missing; every scene has particles (adapter: liggghts or free-particles)");
  }
  return out;
}

}  // namespace cosim::orchestrator
