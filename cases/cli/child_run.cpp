#include "cases/cli/child_run.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <limits>

#include <toml++/toml.h>

namespace hvi::driver {

std::string shell_quote(const std::string& s) {
  std::string out(1, '\'');
  for (const char c : s) {
    if (c == '\'') {
      out.append("'\\''");
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

int run_child(const std::string& hvi, const std::vector<std::string>& args,
              const std::filesystem::path& log, bool append, const std::string& launcher) {
  std::string command = (launcher.empty() ? "" : launcher + " ") + shell_quote(hvi);
  for (const auto& a : args) {
    command.push_back(' ');
    command.append(shell_quote(a));
  }
  command.append(append ? " >> " : " > ");
  command.append(shell_quote(log.string()));
  command.append(" 2>&1");
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

ChildLog read_child_log(const std::filesystem::path& log, std::uintmax_t from,
                        const std::string& scene_file) {
  ChildLog said;
  std::ifstream in(log);
  in.seekg(static_cast<std::streamoff>(from));
  const std::string banner = "hvi: " + scene_file;
  std::string line;
  while (std::getline(in, line)) {
    const auto text = line.find_first_not_of(' ');
    if (text == std::string::npos) continue;
    const std::string_view l = std::string_view(line).substr(text);
    if (l.starts_with("warning: ")) {
      said.warnings.emplace_back(l);
    } else if (text == 0 && l.starts_with("hvi: ")) {
      const bool is_banner =
          l.starts_with("hvi: resuming ") || l == banner || l.starts_with(banner + " — ");
      if (!is_banner) said.outcome.emplace_back(l);
    }
  }
  return said;
}

RunSummary read_run_summary(const std::filesystem::path& run_dir) {
  RunSummary s;
  const auto file = run_dir / "summary.toml";
  if (!std::filesystem::exists(file)) return s;
  const toml::table t = toml::parse_file(file.string());
  s.status = t["status"].value_or(std::string{});
  // All the invocations of a resumed run, where its checkpoint recorded them.
  s.wall_seconds = t["wall_seconds_total"].value_or(t["wall_seconds"].value_or(0.0));
  s.peak_memory = static_cast<double>(t["peak_memory_bytes"].value_or(std::int64_t{0}));
  if (const auto m = t["peak_memory_with_measure_bytes"].value<std::int64_t>())
    s.peak_memory_with_measure = static_cast<double>(*m);
  s.particles = static_cast<double>(t["particles"].value_or(std::int64_t{0}));
  s.steps = static_cast<double>(t["steps"].value_or(std::int64_t{0}));
  s.energy_balance = t["energy_balance"].value_or(0.0);
  if (const auto* m = t["measures"].as_table())
    for (const auto& [k, v] : *m)
      s.measures[std::string(k.str())] = v.value_or(std::numeric_limits<double>::quiet_NaN());
  return s;
}

}  // namespace hvi::driver
