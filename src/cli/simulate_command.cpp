// `layerjkr simulate`: the library's synthetic curve, written as a CSV the fit reads back.
#include "simulate_command.hpp"

#include <iostream>

#include "files.hpp"
#include "limits.hpp"
#include "output_file.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr::cli {

void add_simulate_options(CLI::App& c, SimulateArguments& a) {
  SimulationOptions& o = a.options;
  c.add_option("scene", a.scene, "Scene JSON file")->required();
  c.add_option("--max-indentation", o.max_indentation, "Deepest indentation beyond first contact [m]")->required();
  c.add_option("--speed", o.speed,
               "The indenter's approach speed [m/s]: the curve in time, with a t column (needed by a relaxing medium "
               "and crack kinetics)");
  c.add_option("--retract-speed", o.retract_speed, "The retract's speed [m/s] (default: --speed)");
  c.add_option("--dwell", o.dwell, "Rest at the deepest point [s] (dwell samples, segment 2; needs --speed)");
  c.add_option("--points", a.points, "Samples per branch (approach, retract; default 500)");
  c.add_option("--free-fraction", o.free_fraction, "Fraction of the indentation sampled off contact (default 0.5)");
  c.add_option("--delta0", o.delta0, "Contact-point offset added to every delta [m]");
  c.add_option("--P0", o.P0, "Force baseline added to every P [N]");
  c.add_option("--noise", o.noise, "Standard deviation of Gaussian force noise [N]");
  c.add_option("--drag", o.drag,
               "The lever's hydrodynamic drag b [N s/m]: every force gains b v, v the base's speed towards the sample "
               "(needs --speed; fit --free drag finds it)");
  a.seed = c.add_option("--seed", o.seed, "Seed of the noise (default 1; needs --noise)");
  c.add_flag("--with-radius", o.with_radius, "Also write the contact radius a [m]");
  c.add_option("--branch", a.branch, "approach, retract or all (default all)");
  c.add_option("--control", a.control,
               "What drives a retract with crack kinetics, or a relaxing adhesive curve throughout: grips (the "
               "indenter follows the ramp) or cantilever (the base of a lever of --stiffness follows it)");
  a.stiffness = c.add_option("--stiffness", o.cantilever_stiffness, "The cantilever's stiffness [N/m] (needs --control cantilever)");
  c.add_option("--out", a.out, "CSV file to write (- or absent: standard output)");
}

int run_simulate(const SimulateArguments& a, const std::string& command_line) {
  SimulationOptions o = a.options;
  check_count("--points", a.points, 2, static_cast<long long>(SimulationOptions::kMaxPointsPerBranch));
  o.points_per_branch = static_cast<std::size_t>(a.points);
  o.branch = parse_enum<Branch>(a.branch, "--branch");
  o.control = parse_enum<RetractControl>(a.control, "--control");
  if (o.control == RetractControl::cantilever && a.stiffness->count() == 0)
    throw InputError("--control cantilever needs the lever's --stiffness [N/m]");
  // An option that cannot apply is refused, not ignored: the user meant something by it.
  if (a.stiffness->count() > 0 && o.control != RetractControl::cantilever)
    throw InputError("--stiffness applies to --control cantilever only (the retract is driven by " + a.control + ")");
  if (a.seed->count() > 0 && !(o.noise > 0.0))
    throw InputError("--seed applies to --noise only, which is " + format_double(o.noise) + " N: without noise there is nothing to draw");
  try {
    o.validate();
  } catch (const DomainError& e) {
    throw InputError("--" + std::string(e.parameter() == "max_indentation" ? "max-indentation"
                                        : e.parameter() == "retract_speed"  ? "retract-speed"
                                        : e.parameter() == "free_fraction"  ? "free-fraction"
                                        : e.parameter() == "cantilever_stiffness" ? "stiffness"
                                                                                   : e.parameter()) +
                     " = " + format_double(e.value()) + " is invalid: " + e.what());
  }
  if (!a.out.empty() && a.out != "-") check_not_input(a.out, "--out", {a.scene});
  const Scene scene = load_scene(a.scene);
  const CurveData c = simulate_curve(scene, o);  // before the output is opened: a failure writes nothing
  const bool timed = !c.t.empty(), radius = !c.a.empty();
  std::string text = "# " + printable(command_line) + "\n";
  for (const std::string& note : c.notes) {  // in the file, with the curve, and said now
    text += "# note: " + printable(note) + "\n";
    std::cerr << "simulate: note: " << printable(note) << "\n";
  }
  text += std::string(timed ? "t," : "") + "delta,P" + (radius ? ",a" : "") + ",segment\n";
  for (std::size_t i = 0; i < c.size(); ++i)
    text += (timed ? format_double(c.t[i]) + "," : std::string()) + format_double(c.delta[i]) + "," +
            format_double(c.P[i]) + (radius ? "," + format_double(c.a[i]) : std::string()) + "," +
            std::to_string(c.segment[i]) + "\n";
  OutputFile out(a.out);
  out.write(text);
  out.commit();
  if (!out.is_standard_output())
    std::cerr << "simulate: " << c.size() << " samples of " << printable(c.source) << " written to " << printable(a.out) << "\n";
  return 0;
}

}  // namespace layerjkr::cli
