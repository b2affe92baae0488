#include "cases/cli/sweep_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cases/cli/child_run.hpp"
#include "cases/parallel/task_queue.hpp"
#include "cases/run/run.hpp"
#include "cases/scene/scene.hpp"
#include "cases/scene/schema.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;
using scene::Diagnostic;
using scene::SceneError;
using scene::TableSpec;

namespace {

const TableSpec& study_schema() {
  static const TableSpec schema = [] {
    TableSpec root;
    root.string("title", "", "A line describing the study")
        .string_required("scene", "The scene every run starts from (relative to the study file)")
        .string_list("set", {}, "Overrides key.path=value for every run (e.g. resolution=coarse)");
    TableSpec level{
        .name = "level", .doc = "One value of an axis", .array = true, .required = true};
    level.string_required("label", "Name of the level in run names and sweep.csv")
        .string_list("set", {}, "Overrides key.path=value of this level");
    TableSpec axis{.name = "axis",
                   .doc = "A parameter varied over levels; the runs are the product of the axes",
                   .array = true};
    axis.string_required("name", "Column of sweep.csv holding the level's label").table(level);
    TableSpec run{.name = "run", .doc = "A run listed on its own", .array = true};
    run.string_required("name", "Name of the run (its directory)")
        .string_list("set", {}, "Overrides key.path=value of this run");
    root.table(axis).table(run);
    return root;
  }();
  return schema;
}

std::vector<std::string> strings(const toml::node* node) {
  std::vector<std::string> out;
  if (const auto* a = node ? node->as_array() : nullptr)
    for (const auto& v : *a) out.push_back(v.value<std::string>().value());
  return out;
}

// The key.path of a key.path=value override, without surrounding blanks.
std::string override_key(const std::string& assignment) {
  const std::string key = assignment.substr(0, assignment.find('='));
  const auto first = key.find_first_not_of(" \t"), last = key.find_last_not_of(" \t");
  return first == std::string::npos ? std::string() : key.substr(first, last - first + 1);
}

bool valid_name(const std::string& name) {
  if (name.empty() || name == "." || name == "..") return false;
  for (const char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return false;
  return true;
}

// CSV cell: quoted when it holds a comma or a quote.
std::string csv(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        cell += c, ++i;
      else if (c == '"')
        quoted = false;
      else
        cell += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back(cell);
      cell.clear();
    } else {
      cell += c;
    }
  }
  cells.push_back(cell);
  return cells;
}

// The single data row of a run's measurements.csv, by column.
std::vector<std::pair<std::string, std::string>> read_measurements(const fs::path& dir) {
  std::ifstream in(dir / "measurements.csv");
  std::string header, row;
  if (!in || !std::getline(in, header) || !std::getline(in, row)) return {};
  const auto h = split_csv_line(header), r = split_csv_line(row);
  std::vector<std::pair<std::string, std::string>> out;
  for (std::size_t k = 0; k < h.size() && k < r.size(); ++k) out.emplace_back(h[k], r[k]);
  return out;
}

std::string number(double v) {
  return std::isfinite(v) ? fmt::format("{:.10g}", v) : "";
}

// sweep.csv from what the run directories hold now.
// Rows: the runs selected now and every other run of the study already in `out`, in the study's
// order, so runs made one `--only` at a time into one directory share one table.
void write_table(const Study& study, const std::vector<std::string>& selected, const fs::path& out,
                 const std::map<std::string, std::string>& status_of) {
  std::vector<SweepRun> runs;
  for (const auto& r : study.runs)
    if (std::find(selected.begin(), selected.end(), r.name) != selected.end() ||
        fs::exists(out / r.name))
      runs.push_back(r);
  std::vector<std::string> axes;
  for (const auto& r : runs)
    for (const auto& [axis, label] : r.labels)
      if (std::find(axes.begin(), axes.end(), axis) == axes.end()) axes.push_back(axis);
  std::vector<std::string> columns{"run"};
  columns.insert(columns.end(), axes.begin(), axes.end());
  for (const char* c : {"status", "wall_seconds", "steps", "particles", "peak_memory_bytes",
                        "peak_memory_with_measure_bytes", "energy_balance"})
    columns.emplace_back(c);
  const std::size_t fixed = columns.size();
  std::vector<std::map<std::string, std::string>> rows;
  for (const auto& r : runs) {
    std::map<std::string, std::string> row{{"run", r.name}};
    for (const auto& [axis, label] : r.labels) row[axis] = label;
    const fs::path dir = out / r.name;
    const RunSummary s = read_run_summary(dir);
    const auto st = status_of.find(r.name);
    row["status"] = st != status_of.end() ? st->second : (s.status.empty() ? "not run" : s.status);
    if (!s.status.empty()) {
      row["wall_seconds"] = number(s.wall_seconds);
      row["steps"] = number(s.steps);
      row["particles"] = number(s.particles);
      row["peak_memory_bytes"] = number(s.peak_memory);
      row["peak_memory_with_measure_bytes"] = number(s.peak_memory_with_measure);
      row["energy_balance"] = number(s.energy_balance);
    }
    auto add = [&](const std::string& column, const std::string& value) {
      if (row.count(column)) return;
      row[column] = value;
      if (std::find(columns.begin() + static_cast<std::ptrdiff_t>(fixed), columns.end(), column) ==
          columns.end())
        columns.push_back(column);
    };
    for (const auto& [column, value] : read_measurements(dir))
      if (column != "run") add(column, value);
    for (const auto& [name, value] : s.measures) add(name, number(value));
    rows.push_back(std::move(row));
  }
  std::ofstream file(out / "sweep.csv");
  for (std::size_t k = 0; k < columns.size(); ++k) file << (k ? "," : "") << csv(columns[k]);
  file << '\n';
  for (const auto& row : rows) {
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const auto it = row.find(columns[k]);
      file << (k ? "," : "") << (it == row.end() ? "" : csv(it->second));
    }
    file << '\n';
  }
}

}  // namespace

Study load_study(const std::string& path, const std::vector<std::string>& overrides) {
  const scene::Validated v =
      scene::validate(scene::read_document(path, "study"), study_schema(), path);
  if (!v.ok()) throw SceneError(v.errors);
  const toml::table& r = v.resolved;
  Study study;
  study.title = r["title"].value<std::string>().value();
  study.scene = (fs::path(path).parent_path() / r["scene"].value<std::string>().value())
                    .lexically_normal()
                    .string();
  // Precedence, the later one winning: the study's own `set`, the run's (its levels' or its
  // [[run]]'s), then the command line's, as for `hvi run` (a scene's file, then --set).
  const std::vector<std::string> common = strings(r.get("set"));
  std::vector<Diagnostic> errors;
  std::set<std::string> axis_keys;  // what some axis varies: the command line must not fix it

  // The product of the axes (the first axis varies slowest).
  std::vector<SweepRun> product;
  if (const auto* axes = r["axis"].as_array(); axes && !axes->empty()) {
    product.push_back(SweepRun{});
    for (std::size_t a = 0; a < axes->size(); ++a) {
      const toml::table& axis = *axes->get(a)->as_table();
      const std::string axis_name = axis["name"].value<std::string>().value();
      std::vector<SweepRun> next;
      for (const auto& partial : product) {
        const toml::array& levels = *axis["level"].as_array();
        for (std::size_t l = 0; l < levels.size(); ++l) {
          const toml::table& level = *levels.get(l)->as_table();
          const std::string label = level["label"].value<std::string>().value();
          if (!valid_name(label))
            errors.push_back(
                v.at(fmt::format("axis.{}.level.{}.label", axis_name, l),
                     "a label is part of a directory name: letters, digits, '_', '-', '.'"));
          SweepRun run = partial;
          run.name += (run.name.empty() ? "" : "_") + label;
          run.labels.emplace_back(axis_name, label);
          for (const auto& s : strings(level.get("set"))) {
            run.overrides.push_back(s);
            axis_keys.insert(override_key(s));
          }
          next.push_back(std::move(run));
        }
      }
      product = std::move(next);
    }
  }
  for (auto& run : product) study.runs.push_back(std::move(run));
  if (const auto* runs = r["run"].as_array())
    for (std::size_t k = 0; k < runs->size(); ++k) {
      const toml::table& t = *runs->get(k)->as_table();
      SweepRun run;
      run.name = t["name"].value<std::string>().value();
      if (!valid_name(run.name))
        errors.push_back(v.at(fmt::format("run.{}.name", run.name),
                              "a run name is a directory name: letters, digits, '_', '-', '.'"));
      run.overrides = strings(t.get("set"));
      study.runs.push_back(std::move(run));
    }
  if (study.runs.empty())
    errors.push_back(v.at("run", "a study needs at least one [[axis]] or [[run]]"));
  std::set<std::string> seen;
  for (auto& run : study.runs) {
    if (!seen.insert(run.name).second)
      errors.push_back(v.at("run", fmt::format("two runs are named '{}'", run.name)));
    std::vector<std::string> all = common;
    all.insert(all.end(), run.overrides.begin(), run.overrides.end());
    all.insert(all.end(), overrides.begin(), overrides.end());
    run.overrides = std::move(all);
  }
  for (const auto& s : overrides)
    if (axis_keys.count(override_key(s)))
      errors.push_back(Diagnostic{
          "--set", 0, 0, override_key(s), s.substr(s.find('=') + 1),
          "an axis of this study varies this key; fixing it on the command line would make "
          "its levels the same run (select runs with --only instead)"});
  if (!errors.empty()) throw SceneError(errors);
  return study;
}

namespace {

// The first dotted key whose value differs between two resolved scenes ("" if none).
std::string first_difference(const toml::table& a, const toml::table& b,
                             const std::string& prefix = "") {
  std::set<std::string> keys;
  for (const auto& [k, v] : a) keys.insert(std::string(k.str()));
  for (const auto& [k, v] : b) keys.insert(std::string(k.str()));
  for (const auto& key : keys) {
    const toml::node* x = a.get(key);
    const toml::node* y = b.get(key);
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (!x || !y) return path;
    if (x->is_table() && y->is_table()) {
      const std::string d = first_difference(*x->as_table(), *y->as_table(), path);
      if (!d.empty()) return d;
      continue;
    }
    std::ostringstream sx, sy;
    x->visit([&](const auto& n) { sx << n; });
    y->visit([&](const auto& n) { sy << n; });
    if (sx.str() != sy.str()) return path;
  }
  return {};
}

// What to do with a run directory that already holds a run of this study's run: nothing new, run
// on to a later end time, or refuse (it was run with another scene).
struct Existing {
  std::optional<double> end_time;  // continue to this end time
  std::string conflict;            // why the directory cannot be used
  std::string own_measures;  // the study's [[measure]] differ from the run's, which it keeps: why
};

Existing compare_existing(const fs::path& dir, const scene::Scene& wanted, bool finished) {
  Existing e;
  if (!fs::exists(dir / "scene.resolved.toml")) return e;
  const scene::Scene have = scene::load_scene((dir / "scene.resolved.toml").string());
  // How far and how often it writes, and what it measures, do not change what a run computes: not
  // compared. A run resumed or run on keeps its own output and measures, as a finished one has
  // them.
  toml::table a = wanted.resolved, b = have.resolved;
  if (a["measure"] != b["measure"]) {
    e.own_measures = "it keeps the [[measure]] it was started with (the study's differ)";
    const bool history = std::any_of(wanted.measures.begin(), wanted.measures.end(),
                                     [](const auto& m) { return m.kind == "holes" && m.history; });
    if (history)
      e.own_measures += fmt::format(
          "; `hvi measure {} --snapshot all` measures its holes at every snapshot", dir.string());
  }
  for (toml::table* t : {&a, &b}) {
    t->erase("output");
    t->erase("measure");
    if (toml::table* r = (*t)["run"].as_table()) {
      r->erase("end_time");
      r->erase("max_steps");
    }
  }
  const std::string key = first_difference(a, b);
  if (!key.empty()) {
    e.conflict = fmt::format(
        "{} was run with another scene than the study's (key '{}' differs); remove it or "
        "choose another --out",
        dir.string(), key);
  } else if (wanted.end_time > have.end_time || (!finished && wanted.end_time != have.end_time)) {
    e.end_time = wanted.end_time;
  } else if (wanted.end_time < have.end_time) {
    e.conflict =
        fmt::format("{} ran to {:g} us but the study now ends at {:g} us; remove it to rerun",
                    dir.string(), have.end_time * 1e6, wanted.end_time * 1e6);
  }
  return e;
}

// The runs --only names, in its order (all when it names none); nullopt after saying which name
// the study lacks.
std::optional<std::vector<SweepRun>> select_runs(const Study& study, const SweepOptions& o) {
  if (o.only.empty()) return study.runs;
  std::vector<SweepRun> kept;
  for (const auto& name : o.only) {
    const auto it = std::find_if(study.runs.begin(), study.runs.end(),
                                 [&](const auto& r) { return r.name == name; });
    if (it == study.runs.end()) {
      std::string names;
      for (const auto& r : study.runs) names += (names.empty() ? "" : ", ") + r.name;
      fmt::print(stderr, "hvi sweep: {} has no run '{}' (runs: {})\n", o.study, name, names);
      return std::nullopt;
    }
    kept.push_back(*it);
  }
  return kept;
}

// Every run's scene is checked before anything runs, so a typo in the last level does not
// surface hours into the study; so is every run already in --out: one run with another scene
// stops the sweep, and one with an earlier end time is run on (resumed) to the study's.
int check_runs(const Study& study, const SweepOptions& o,
               std::map<std::string, Existing>& existing) {
  for (const auto& run : study.runs) {
    try {
      const scene::Scene wanted = scene::load_scene(study.scene, run.overrides);
      if (!o.list) {
        const fs::path dir = fs::path(o.out) / run.name;
        existing[run.name] = compare_existing(dir, wanted, read_run_summary(dir).finished());
      }
    } catch (const SceneError& e) {
      for (const auto& d : e.diagnostics()) fmt::print(stderr, "{}\n", d.text());
      fmt::print(stderr, "hvi sweep: run '{}' of {} has an invalid scene; nothing was run\n",
                 run.name, o.study);
      return input_error;
    }
    if (!existing[run.name].conflict.empty()) {
      fmt::print(stderr, "hvi sweep: {}; nothing was run\n", existing[run.name].conflict);
      return input_error;
    }
  }
  return success;
}

// The `hvi run` arguments that start run k, resume it, or run it on to `extend`.
std::vector<std::string> run_arguments(const SweepOptions& o, const Study& study,
                                       const SweepRun& run, const fs::path& dir, bool resume,
                                       std::optional<double> extend) {
  std::vector<std::string> args;
  if (resume) {
    args = {"run", "--resume", dir.string()};
    // hvi run --resume removes the measurements of the earlier end, so the run is measured again.
    if (extend) args.insert(args.end(), {"--set", fmt::format("run.end_time={:.17g}", *extend)});
  } else {
    args = {"run", study.scene, "--out", dir.string(), "--overwrite"};
    for (const auto& s : run.overrides) args.insert(args.end(), {"--set", s});
  }
  if (o.threads > 0) args.insert(args.end(), {"--threads", std::to_string(o.threads)});
  return args;
}

// What starts a run's ranks: the launcher with its count, or nothing for a run of one rank.
std::string launcher_command(const SweepOptions& o) {
  if (o.ranks_per_run <= 1) return {};
  std::string command = o.launcher;
  for (auto at = command.find("{ranks}"); at != std::string::npos; at = command.find("{ranks}"))
    command.replace(at, 7, std::to_string(o.ranks_per_run));
  return command;
}

// The start of a run's follow-up lines on the console. On several ranks the runs' lines
// interleave, so each names its run.
std::string under(const SweepOptions& o, const SweepRun& run, int indent = 4) {
  return std::string(static_cast<std::size_t>(indent), ' ') +
         (o.ranks > 1 ? run.name + ": " : std::string{});
}

// Runs (or resumes, or runs on) run k as a child `hvi run` and says how it ended. Returns the
// child's exit status; `summary` is the run's afterwards, `outcome` says "failed" or "stopped" for
// a run that did not finish.
int run_one(const SweepOptions& o, const Study& study, std::size_t k, const Existing& existing,
            RunSummary& summary, std::string& outcome) {
  const SweepRun& run = study.runs[k];
  const fs::path dir = fs::path(o.out) / run.name;
  const std::optional<double> extend = existing.end_time;
  const bool resume = fs::exists(dir / "checkpoint.h5") && fs::exists(dir / "scene.resolved.toml");
  const std::vector<std::string> args = run_arguments(o, study, run, dir, resume, extend);
  fmt::print("[{}/{}] {}: {}...{}\n", k + 1, study.runs.size(), run.name,
             !resume                        ? "running"
             : extend && summary.finished() ? fmt::format("running on to {:g} us", *extend * 1e6)
                                            : "resuming",
             o.ranks > 1 ? fmt::format(" (rank {})", o.rank) : "");
  if (resume && !existing.own_measures.empty())
    fmt::print("{}{}\n", under(o, run), existing.own_measures);
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  // The log names the run (the base scene's title is the same for every run) and keeps the
  // earlier parts of a resumed or extended run.
  const fs::path run_log = fs::path(o.out) / (run.name + ".log");
  {
    std::ofstream header(run_log, resume ? std::ios::app : std::ios::trunc);
    header << fmt::format("hvi sweep: run '{}' of {}: {} {}\n", run.name, o.study, study.scene,
                          fmt::join(run.overrides, " "));
  }
  const std::uintmax_t log_start = fs::file_size(run_log);
  const int status = run_child(o.hvi, args, run_log, true, launcher_command(o));
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  summary = read_run_summary(dir);
  if (stopped_by_signal(status)) return status;
  // The run's own account of how it ended, and its warnings (a disk too small for its output,
  // say), on the console: a sweep of hours is watched there, not in each run's log.
  const ChildLog said = read_child_log(run_log, log_start, study.scene);
  if (status != success || !summary.finished()) {
    const bool stopped = status == success && summary.status == "stopped";
    outcome = stopped ? "stopped" : "failed";
    fmt::print("{}{} after {:.1f} s (exit {}); see {}\n", under(o, run),
               stopped ? "stopped" : "failed", wall, status, run_log.string());
    for (const auto& line : said.outcome) fmt::print("{}{}\n", under(o, run, 6), line);
  } else {
    fmt::print("{}finished in {:.1f} s\n", under(o, run), wall);
  }
  for (const auto& line : said.warnings) fmt::print("{}{}\n", under(o, run, 6), line);
  return status;
}

// Run k of the study on this rank: skipped if done, else run, resumed or run on; then measured.
// The result's code is the run's exit status, its status what sweep.csv says of an unfinished run.
parallel::TaskResult sweep_run(const SweepOptions& o, const Study& study, std::size_t k,
                               const Existing& e) {
  const SweepRun& run = study.runs[k];
  const fs::path dir = fs::path(o.out) / run.name;
  RunSummary summary = read_run_summary(dir);
  parallel::TaskResult result;
  if (summary.finished() && !e.end_time) {
    fmt::print("[{}/{}] {}: done ({:.1f} s)\n", k + 1, study.runs.size(), run.name,
               summary.wall_seconds);
    if (!e.own_measures.empty()) fmt::print("{}{}\n", under(o, run), e.own_measures);
  } else {
    result.code = run_one(o, study, k, e, summary, result.status);
    if (stopped_by_signal(result.code)) return result;
    if (result.code == success && !summary.finished()) result.code = run_failed;
  }
  if (summary.finished() && !fs::exists(dir / "measurements.csv")) {
    const int status = run_child(o.hvi, {"measure", dir.string()}, dir / "measure.log");
    if (status != success)
      fmt::print("{}not measured (see {})\n", under(o, run), (dir / "measure.log").string());
  }
  std::fflush(stdout);
  return result;
}

}  // namespace

int run_sweep(const SweepOptions& options, const parallel::Ranks& ranks) {
  return run_study(load_study(options.study, options.overrides), options, ranks);
}

int run_study(const Study& whole, const SweepOptions& options, const parallel::Ranks& ranks) {
  SweepOptions o = options;
  o.rank = ranks.rank();
  o.ranks = ranks.size();
  if (o.ranks_per_run > 1 && o.ranks > 1) {
    if (ranks.root())
      fmt::print(stderr,
                 "hvi sweep: --ranks-per-run starts each run as an MPI job of its own "
                 "(`{}`); start the sweep itself without mpirun\n",
                 launcher_command(o));
    return input_error;
  }
  Study study = whole;  // sweep.csv keeps the rows of runs made by earlier `--only`s
  auto selected_runs = select_runs(study, o);
  if (!selected_runs) return input_error;
  study.runs = std::move(*selected_runs);
  std::map<std::string, Existing> existing;
  if (const int code = check_runs(study, o, existing); code != success) return code;
  if (ranks.root() && !o.quiet_start)
    fmt::print("hvi sweep: {}{} — {} run{} of {}{}\n", o.study,
               study.title.empty() ? "" : " (" + study.title + ")", study.runs.size(),
               study.runs.size() == 1 ? "" : "s", study.scene,
               ranks.size() > 1      ? fmt::format(", handed out to {} ranks", ranks.size())
               : o.ranks_per_run > 1 ? fmt::format(", each an MPI job: {}", launcher_command(o))
                                     : "");
  if (o.list) {
    if (ranks.root())
      for (const auto& run : study.runs)
        fmt::print("  {}: {}\n", run.name, fmt::join(run.overrides, " "));
    return success;
  }
  fs::create_directories(o.out);
  std::map<std::string, std::string> status_of;
  std::vector<std::string> selected;
  for (const auto& run : study.runs) selected.push_back(run.name);
  int code = success;
  std::optional<std::string> interrupted;
  parallel::share_tasks(
      ranks, study.runs.size(),
      [&](std::size_t k) { return sweep_run(o, study, k, existing.at(study.runs[k].name)); },
      [&](std::size_t k, const parallel::TaskResult& r) {
        const std::string& name = study.runs[k].name;
        if (!r.status.empty()) status_of[name] = r.status;
        if (stopped_by_signal(r.code)) {
          interrupted = interrupted.value_or(name);
          code = r.code;
        } else if (r.code != success && code == success) {
          code = run_failed;
        }
        // After every run: the table is current even if the sweep is stopped.
        write_table(whole, selected, o.out, status_of);
        return !interrupted;
      });
  if (!ranks.root()) return success;  // rank 0 reports for the job
  if (interrupted) {
    fmt::print("hvi sweep: interrupted in {}; run the same command again to resume\n",
               *interrupted);
    return code;
  }
  if (o.quiet_end) return code;
  fmt::print("hvi sweep: {} (one row per run); hvi fit {} --form front|rear|taper; hvi report {}\n",
             (fs::path(o.out) / "sweep.csv").string(), o.out, o.out);
  return code;
}

}  // namespace hvi::driver
