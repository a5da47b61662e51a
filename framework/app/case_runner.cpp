#include "case_runner.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "code_fingerprint.hpp"
#include "distribution.hpp"
#include "interrupt.hpp"
#include "io/atomic_file.hpp"
#include "spawn.hpp"
#include "topomill/error.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace topomill::cli {

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> run_args(const Case& c, const RunnerOptions& o, const fs::path& dir) {
  std::vector<std::string> a = {
      "run", o.scene_file, "-q", "--out", dir.string(), "--threads", std::to_string(o.threads)};
  a.insert(a.end(), o.extra_args.begin(), o.extra_args.end());
  for (const auto& s : c.overrides) a.push_back("--set"), a.push_back(s);
  return a;
}

std::string joined(const std::vector<std::string>& args) {
  std::string s;
  for (const auto& a : args) s += a + '\n';
  return s;
}

// The case's own record of what it ran, to tell a finished case from one of another sweep.
fs::path args_file(const fs::path& dir) {
  return dir.string() + ".args";
}
fs::path log_file(const fs::path& dir) {
  return dir.string() + ".log";
}

bool already_done(const fs::path& dir, const std::vector<std::string>& args,
                  const std::string& scene) {
  const fs::path summary = dir / "summary.json";
  std::error_code ec;
  if (!fs::exists(summary) || slurp(args_file(dir)) != joined(args)) return false;
  // An edited scene invalidates earlier results.
  if (fs::last_write_time(summary, ec) < fs::last_write_time(scene, ec)) return false;
  // So does other code: a rebuilt program, core or plugin library (by their bytes, not times).
  try {
    const json j = json::parse(slurp(summary));
    for (const auto& f : j.at("files"))  // a case whose files went missing is not done
      if (!fs::is_regular_file(dir / f.get<std::string>(), ec)) return false;
    // Nor one whose models read a file that has changed since (cutter-location data): by bytes.
    if (j.contains("inputs"))
      for (const auto& in : j.at("inputs"))
        if (file_checksum(in.at("file").get<std::string>()) != in.at("crc32").get<std::string>())
          return false;
    std::vector<std::string> libraries;
    for (const auto& [slot, entry] : j.at("plugins").items())
      libraries.push_back(entry.at("library").get<std::string>());
    return j.at("topomill").at("code_fingerprint").get<std::string>() ==
           code_fingerprint(libraries);
  } catch (const json::exception&) {
    return false;
  }
}

CaseResult from_summary(const std::string& id, const fs::path& dir) {
  CaseResult r;
  r.id = id;
  r.dir = dir.string();
  const json j = json::parse(slurp(dir / "summary.json"));
  r.ok = true;
  // A parameter undefined for this case's surface ({"undefined": why}) is left out: the tables
  // show it as missing, not as a number.
  for (const auto& [k, v] : j.at("roughness").items())
    if (v.contains("value")) r.roughness[k] = v.at("value").get<double>();
  const json& timing = j.at("timing_s");
  r.wall_s = timing.at("total").get<double>();
  for (const auto& s : j.at("stages")) {
    const std::string name = s.get<std::string>();
    r.stages.emplace_back(name, timing.at(name).get<double>());
  }
  for (const auto& [k, v] : j.at("work").items()) r.work[k] = v.get<std::uint64_t>();
  const json& g = j.at("grid").at("zmap");
  r.work["grid_nodes"] = g.at("nx").get<std::uint64_t>() * g.at("ny").get<std::uint64_t>();
  for (const auto& e : j.at("effects")) r.effects.push_back(e.get<std::string>());
  return r;
}

// The line of the log that says what went wrong.
std::string failure_message(const fs::path& log, int status) {
  std::istringstream in(slurp(log));
  std::string line, last, error;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    last = line;
    if (error.empty() && line.find("error") != std::string::npos) error = line;
  }
  if (!error.empty()) return error;
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return last.empty() ? "failed without a message" : last;
}

json to_json(const CaseResult& r) {
  json j = {{"id", r.id},           {"ok", r.ok},
            {"resumed", r.resumed}, {"exit_code", r.exit_code},
            {"error", r.error},     {"roughness", r.roughness},
            {"wall_s", r.wall_s},   {"stages", r.stages},
            {"work", r.work},       {"effects", r.effects},
            {"dir", r.dir},         {"rank", r.rank}};
  return j;
}

CaseResult from_json(const json& j) {
  CaseResult r;
  r.id = j.at("id");
  r.ok = j.at("ok");
  r.resumed = j.at("resumed");
  r.exit_code = j.at("exit_code");
  r.error = j.at("error");
  r.roughness = j.at("roughness").get<std::map<std::string, double>>();
  r.wall_s = j.at("wall_s");
  r.stages = j.at("stages").get<std::vector<std::pair<std::string, double>>>();
  r.work = j.at("work").get<std::map<std::string, std::uint64_t>>();
  r.effects = j.at("effects").get<std::vector<std::string>>();
  r.dir = j.at("dir");
  r.rank = j.at("rank");
  return r;
}

}  // namespace

std::string case_id(const std::string& text) {
  std::string id;
  for (char ch : text)
    id += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '=' || ch == '-')
              ? ch
              : '_';
  return id;
}

void check_case_ids(const std::vector<Case>& cases) {
  std::set<std::string> ids;
  for (const auto& c : cases)
    if (!ids.insert(c.id).second)
      throw InputError(
          SourceRef{"command line"}, "--vary/--swap/--spacing",
          "two cases would share the directory '" + c.id + "': a value is given twice");
}

std::vector<CaseResult> run_cases(const std::vector<Case>& cases, const RunnerOptions& o) {
  const Distribution& mpi = Distribution::instance();
  const fs::path root = fs::path(o.out_dir) / "cases";
  check_case_ids(cases);
  fs::create_directories(root);

  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(mpi.ranks())) == mpi.rank())
      mine.push_back(i);

  std::vector<CaseResult> results;
  std::map<pid_t, std::size_t> running;  // pid -> case index
  // Should this process die without stopping its cases, each is told (main.cpp).
  setenv("TOPOMILL_STOP_WITH_PARENT", std::to_string(getpid()).c_str(), 1);
  std::size_t next = 0, finished = 0;
  auto report = [&](CaseResult& r) {
    r.rank = mpi.rank();
    ++finished;
    if (!o.progress) return;
    // One write a line: std::cerr writes each piece at once, and under mpirun the ranks' pieces
    // would interleave within lines.
    std::ostringstream line;
    line << (mpi.ranks() > 1 ? "rank " + std::to_string(mpi.rank()) + " " : "") << "[" << finished
         << "/" << mine.size() << "] " << r.id << ": "
         << (r.ok ? (r.resumed ? "done earlier" : "ok") : "FAILED: " + r.error) << "\n";
    std::cerr << line.str() << std::flush;
  };
  auto collect = [&](pid_t pid, int status) {
    const std::size_t i = running.at(pid);
    running.erase(pid);
    const fs::path dir = root / cases[i].id;
    CaseResult r;
    const bool exited_ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (exited_ok && fs::exists(dir / "summary.json")) {
      r = from_summary(cases[i].id, dir);
    } else {
      r.id = cases[i].id;
      r.dir = dir.string();
      r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      r.error = failure_message(log_file(dir), status);
      fs::remove(args_file(dir));
    }
    report(r);
    results.push_back(r);
  };

  while (next < mine.size() || !running.empty()) {
    if (stop_flag().load()) {
      // The same signal to every running case (each in a process group of its own, which a
      // terminal's Ctrl-C, a `timeout` or a scheduler's SIGTERM to this process do not reach).
      for (const auto& [pid, i] : running) kill(pid, stop_signal());
      while (!running.empty()) {
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid > 0) running.erase(pid);
      }
      throw Interrupted("interrupted (" + signal_name(stop_signal()) +
                        "): the running cases were stopped and wrote nothing; the finished "
                        "ones are kept: rerun the same command to go on");
    }
    if (next < mine.size() && running.size() < std::max(1u, o.jobs)) {
      const Case& c = cases[mine[next++]];
      const fs::path dir = root / c.id;
      const auto args = run_args(c, o, dir);
      if (already_done(dir, args, o.scene_file)) {
        CaseResult r = from_summary(c.id, dir);
        r.resumed = true;
        report(r);
        results.push_back(r);
        continue;
      }
      write_atomically(args_file(dir).string(), [&](std::ostream& out) { out << joined(args); });
      // Each case in a process group of its own: a Ctrl-C reaches the sweep, which stops them.
      running[spawn_logged("/proc/self/exe", args, log_file(dir).string(), true)] = mine[next - 1];
      continue;
    }
    // Polling, so that a Ctrl-C arriving just before the wait is seen within 20 ms.
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0 && running.count(pid))
      collect(pid, status);
    else if (pid == 0)
      usleep(20000);
  }

  // Gather on rank 0, in the cases' order.
  std::vector<std::string> packed;
  for (const auto& r : results) packed.push_back(to_json(r).dump());
  std::map<std::string, CaseResult> by_id;
  for (const auto& s : mpi.gather(packed)) {
    CaseResult r = from_json(json::parse(s));
    by_id[r.id] = r;
  }
  std::vector<CaseResult> ordered;
  for (const auto& c : cases)
    if (by_id.count(c.id)) ordered.push_back(by_id[c.id]);
  return ordered;
}

}  // namespace topomill::cli
