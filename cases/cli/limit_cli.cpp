#include "cases/cli/limit_cli.hpp"

#include <CLI/CLI.hpp>

namespace hvi::driver {

std::unique_ptr<ValidateCli> add_validate_command(CLI::App& app) {
  auto cli = std::make_unique<ValidateCli>();
  ValidateOptions& o = cli->options;
  cli->command = app.add_subcommand(
      "validate",
      "Run the shots of an experiment database and compare outcomes with the SRL "
      "ballistic limit equation's and the experiments'");
  cli->command
      ->add_option("database", o.database, "Database CSV (cases/experiments/hcsp_shots.csv)")
      ->required();
  cli->command->add_option("--out", o.out, "Output directory (one run per shot inside)")
      ->required();
  cli->command->add_option("--template", o.template_scene,
                           "Scene every shot starts from (default: shot.toml beside the database)");
  cli->command->add_option("--only", o.only, "Run only these shots (shot ids or run names)");
  cli->command->add_option("--set", o.overrides,
                           "Override a scene key in every shot: key.path=value (repeatable)");
  cli->command->add_option("--threads", o.threads, "OpenMP threads of each run")
      ->check(CLI::Range(1, 1024));
  cli->command->add_option("--criterion", o.criterion,
                           "What fails the rear sheet: hole, spall or either (default)");
  cli->command->add_flag("--list", o.list, "Print the shots' runs with their overrides and exit");
  return cli;
}

std::unique_ptr<BallisticLimitCli> add_ballistic_limit_command(CLI::App& app) {
  auto cli = std::make_unique<BallisticLimitCli>();
  BallisticLimitOptions& o = cli->options;
  CLI::App* c = app.add_subcommand(
      "ballistic-limit",
      "The critical projectile diameter at each speed (or speed at a diameter) by trial runs");
  cli->command = c;
  c->add_option("scene", o.scene, "Scene file (TOML) with a sphere projectile and one panel")
      ->required();
  c->add_option("--out", o.out, "Output directory")->required();
  c->add_option("--speeds", o.speeds, "Speeds, e.g. 2,3,4,5,6,7km/s")->required();
  c->add_option("--vary", o.vary, "diameter (default) or velocity");
  c->add_option("--diameter", o.diameter, "With --vary velocity: the projectile diameter");
  c->add_option("--tolerance", o.tolerance, "Bracket width at which a search stops (0.05: 5%)")
      ->check(CLI::Range(0.001, 1.0));
  c->add_option("--max-trials", o.max_trials, "Trials per search at most")
      ->check(CLI::Range(1, 100));
  c->add_option("--criterion", o.criterion, "What fails the rear sheet: hole, spall or either");
  c->add_option("--start-from", o.start_from,
                "A speed's first trial: neighbour (a converged speed's limit, default) or srl");
  c->add_option("--parallel-searches", o.parallel_searches,
                "With --start-from neighbour: speeds searched at once (default 1; under mpirun, "
                "up to the ranks)")
      ->check(CLI::Range(1, 1000));
  c->add_option("--projectile", o.projectile, "The sphere body varied (default: projectile)");
  c->add_option("--rear-yield", o.rear_yield,
                "Rear sheet's yield for the SRL equation (default: its Johnson-Cook A)");
  c->add_option("--database", o.database,
                "Experiments to plot (default: hcsp_shots.csv beside the scene)");
  c->add_option("--threads", o.threads, "OpenMP threads of each run")->check(CLI::Range(1, 1024));
  c->add_option("--set", o.overrides, "Override a scene key: key.path=value (repeatable)");
  return cli;
}

}  // namespace hvi::driver
