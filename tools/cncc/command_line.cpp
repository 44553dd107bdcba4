// The options and subcommands of the command line (command_line.h).
#include "command_line.h"

#include "targets.h"

#include <fmt/format.h>

namespace cncc::driver {

std::string helpFooter() {
  std::string footer = "\nTargets:\n";
  for (const backends::TargetInfo* target : backends::allTargetInfos()) {
    footer += fmt::format("  {:<11}{}\n", target->name, target->description);
  }
  footer += "\nExamples:\n"
            "  cncc examples/s_profile.cdl -t m80 -o O1000\n"
            "  cncc check examples/*.cdl\n"
            "  cncc fmt -i examples/*.cdl\n"
            "  cncc --emit=ast examples/s_profile.cdl\n"
            "  cncc examples/s_profile.cdl -t gcode --stats -o O1\n"
            "  cncc plot examples/s_profile.cdl -o s_profile.svg\n"
            "  cncc examples/s_profile.cdl --machine examples/machines/fanuc-0i-mf-vmc.toml\n"
            "\nExit codes: 0 success, 1 errors in the source, 2 wrong usage.";
  return footer;
}

// Options shared by every command (compiling, emitting, checking).
void addCommonOptions(CLI::App& app, RawOptions& raw) {
  app.add_option("-D", raw.defines, "Override the default of part parameter NAME")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  app.add_option("-p,--part", raw.partName, "The part to compile when a file holds several")
      ->type_name("PART");
  app.add_option("-I", raw.includeDirectories,
                 "Search DIR for imports (before the standard library)")
      ->type_name("DIR")
      ->allow_extra_args(false);
  app.add_option("--diagnostics-format", raw.diagnosticsFormat,
                 "How diagnostics are printed: text, or json (one object per line)")
      ->type_name("FORMAT")
      ->check(CLI::IsMember({"text", "json"}));
  app.add_option("--color", raw.colour,
                 "Colour diagnostics: auto (when stderr is a terminal), "
                 "always or never")
      ->type_name("WHEN")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  app.add_option("--error-limit", raw.errorLimit, "Stop reporting after N errors (0: no limit)")
      ->type_name("N");
  app.add_option("--machine", raw.machineFile,
                 "The machine's set-up blocks, program format, controller profile and limits "
                 "from a machine file (examples/machines), or a shipped machine's name (fanuc, "
                 "m80, linuxcnc, sinumerik, gcode: the built-in defaults); its target is the "
                 "default of -t")
      ->type_name("FILE.toml");
  app.add_flag("--list-diagnostics", raw.listDiagnostics,
               "Print the name of every diagnostic and exit")
      ->group("");
}

void addCompileOptions(CLI::App& app, RawOptions& raw) {
  app.add_option("FILE", raw.input, "The .cdl file to compile")->type_name("");
  app.add_option("-t,--target", raw.target, "The controller to compile for (see Targets below)")
      ->type_name("TARGET");
  app.add_option("-o,--output", raw.output, "Where to write the program ('-': standard output)")
      ->type_name("OUT");
  app.add_option("--emit", raw.emit,
                 "Print a stage instead of compiling: tokens, ast (after checking), or ir "
                 "(the part lowered)")
      ->type_name("STAGE")
      ->check(CLI::IsMember({"tokens", "ast", "ir"}));
  app.add_flag("--macro", raw.macroCall,
               "m80/fanuc: print a macro called with G65 P.. and arguments, ending M99; "
               "linuxcnc: an o<part> sub taking the parameters as call arguments");
  app.add_option("--params", raw.parameterStorage,
                 "m80/fanuc: part parameters as G65 argument locals, or in common variables")
      ->type_name("local|common")
      ->check(CLI::IsMember({"local", "common"}));
  app.add_option("--profile", raw.profile,
                 "m80/fanuc: the controller profile (fanuc, fanuc-0i-small, m80); "
                 "heidenhain: tnc640 or itnc530")
      ->type_name("NAME")
      ->check(CLI::IsMember({"fanuc", "fanuc-0i-small", "m80", "tnc640", "itnc530"}));
  app.add_flag(
      "--arcs", raw.arcs,
      "gcode, linuxcnc, m80, fanuc: cut planar curves as G02/G03 arcs within their tolerance "
      "(as arcs=true on every cut)");
  app.add_flag("--subprograms", raw.subprograms,
               "sinumerik: each cut's spline blocks in a subprogram NAME_CUTn.SPF called at "
               "every pass (after the main program, in archive form)");
  app.add_option("--spline-ends", raw.splineEnds,
                 "sinumerik: how A and C splines start and end: BTAN after a move in XY and "
                 "BNAT otherwise (tangent, the default), BNAT ENAT, or BAUTO EAUTO")
      ->type_name("tangent|natural|auto")
      ->check(CLI::IsMember({"tangent", "natural", "auto"}));
  app.add_flag("--stats", raw.stats,
               "Also print, on stderr, the program's size, path length, time estimate and "
               "largest deviation from the true curves");
  app.add_option("--rapid-rate", raw.rapidRate,
                 "The rapid rate the --stats time estimate assumes (default 10000)")
      ->type_name("MM/MIN");
  app.add_flag("--annotate", raw.annotate,
               "Put a comment naming the CDL file and line before the first block of each cut");
  app.add_option("--source-map", raw.sourceMap,
                 "Also write where each program line comes from: CDL file, line and column, "
                 "for 'cncc where' (JSON)")
      ->type_name("FILE.json");
  // Written -MD, -MF, -MT as C compilers have them (parseCommandLine).
  app.add_flag("--MD", raw.writeDependencies,
               "-MD: also write a Make/Ninja depfile: the source, its imports and the machine "
               "file (OUT.d unless -MF names it)");
  app.add_option("--MF", raw.dependencyFile, "-MF: the depfile's path")->type_name("FILE");
  app.add_option("--MT", raw.dependencyTarget, "-MT: the target the depfile names (default OUT)")
      ->type_name("TARGET");
}

CLI::App* addCheckCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* check =
      app.add_subcommand("check", "Check files and report every problem without compiling");
  check->add_option("FILE", raw.checkInputs, "The .cdl files to check")->type_name("");
  // The common options belong to the main command and fall through to here.
  check->fallthrough();
  check->footer("\nAlso takes -D, -p, -I, --diagnostics-format, --color and --error-limit "
                "(see 'cncc --help'); with --machine FILE.toml it checks the machine file too, "
                "or alone.\nExit codes: 0 no errors, 1 errors in some file, 2 wrong "
                "usage.");
  return check;
}

CLI::App* addFormatCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* format = app.add_subcommand(
      "fmt",
      "Print files in the canonical layout (see frontend/include/cncc/frontend/formatter.h)");
  format->add_option("FILE", raw.formatInputs, "The .cdl files ('-': standard input)")
      ->type_name("")
      ->required();
  format->add_flag("--check", raw.formatCheck,
                   "Write nothing; list the files that are not formatted (exit code 1 if any)");
  format->add_flag("-i,--in-place", raw.formatInPlace, "Rewrite the files that are not formatted");
  format->fallthrough();
  format->footer("\nExit codes: 0 done, 1 syntax errors (such a file is left as it is) or, with "
                 "--check, unformatted files, 2 wrong usage.");
  return format;
}

CLI::App* addPlotCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* plot = app.add_subcommand(
      "plot", "Draw the part's true curves and emitted path, coloured by deviation, as SVG");
  plot->add_option("FILE", raw.plotInput, "The .cdl file to plot")->type_name("")->required();
  plot->add_option("--format", raw.plotFormat,
                   "svg (the default), or png through rsvg-convert (Debian: librsvg2-bin)")
      ->type_name("svg|png")
      ->check(CLI::IsMember({"svg", "png"}));
  plot->fallthrough();
  plot->footer("\nTakes -o OUT.svg (or OUT.png with --format=png; '-': standard output), "
               "-t TARGET (gcode or jit; gcode by "
               "default), -D, -p, -I and the diagnostic options (see 'cncc --help').");
  return plot;
}

// cncc opt: IR passes on a textual IR file; -O and --print-after are
// options of the main command that fall through to it.
CLI::App* addOptCommand(CLI::App& app, RawOptions& raw) {
  app.add_option("--print-after", raw.printAfter,
                 "Print the IR to stderr after each run of IR pass NAME (or all)")
      ->type_name("NAME");
  app.add_option("-O", raw.optimisationLevel, "-O0: skip the IR optimiser (-O1, the default)")
      ->type_name("LEVEL")
      ->check(CLI::IsMember({"0", "1"}));
  CLI::App* opt = app.add_subcommand("opt", "Run IR passes on a textual IR file and print it");
  opt->add_option("FILE", raw.optInput, "The .ir file")->type_name("")->required();
  opt->add_option("--passes", raw.passes, "Comma-separated pass names (default: the pipeline)")
      ->type_name("A,B");
  opt->fallthrough();
  return opt;
}

// cncc sim: -t, -o and --profile are the main command's options.
CLI::App* addSimulateCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* simulate = app.add_subcommand(
      "sim",
      "Run an m80/fanuc/linuxcnc/sinumerik/heidenhain program on a virtual controller and print "
      "its path as CSV");
  simulate->add_option("PROGRAM", raw.simulateInput, "The program file")->type_name("")->required();
  simulate
      ->add_option("-a", raw.macroArguments,
                   "Run the program as if called by G65 with this argument (A3.)")
      ->type_name("ARG")
      ->allow_extra_args(false);
  simulate->add_flag("--strict", raw.strictReading,
                     "Read the program as the compiler prints it: ( ) comments in upper case, "
                     "no ';', macro words in full");
  simulate
      ->add_option("--tool-radius", raw.toolRadii,
                   "The radius in offset register N, read by D N for G41/G42 (1=5.); "
                   "on sinumerik the radius of tool N's cutting edges, on heidenhain the "
                   "tool table's R of tool N, read by RL/RR; on linuxcnc the tool table's radius "
                   "of tool N, read by G41/G42 D N")
      ->type_name("N=R")
      ->allow_extra_args(false);
  simulate
      ->add_option("--peck-retract", raw.peckRetract,
                   "G73's retract after each peck (Fanuc parameter 5114)")
      ->type_name("D")
      ->check(CLI::NonNegativeNumber);
  simulate
      ->add_option("--peck-clearance", raw.peckClearance,
                   "G83's clearance above the last depth (Fanuc parameter 5115)")
      ->type_name("D")
      ->check(CLI::NonNegativeNumber);
  simulate
      ->add_option("--chord-error", raw.chordError,
                   "The largest distance between an arc and the chords printed for it "
                   "(default 0.0001)")
      ->type_name("MM")
      ->check(CLI::Range(1e-6, 10.0));
  simulate->fallthrough();
  simulate->footer(
      "\nTakes -t fanuc|m80|linuxcnc|sinumerik|heidenhain, --profile NAME and -o OUT ('-': "
      "standard output).");
  return simulate;
}

// cncc verify: the compile options (-t, -D, -p, --profile, --macro,
// --params) are the main command's.
CLI::App* addVerifyCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* verify = app.add_subcommand(
      "verify", "Compile for a target, run the program as its controller would and check it "
                "against the true curves");
  verify->add_option("FILE", raw.verifyInput, "The .cdl file")->type_name("")->required();
  verify->fallthrough();
  verify->footer("\nTakes -t TARGET, -D NAME=VALUE (m80/fanuc: set on the controller, as G65 "
                 "arguments with --macro, common variables with --params common, else in the "
                 "program's parameter lines), -p, -I, --profile, --macro, --params and the "
                 "diagnostic options.\nExit codes: 0 every cut within its tolerance, 1 a cut "
                 "exceeds it, the controller refuses the program or the source has errors, 2 "
                 "wrong usage.");
  return verify;
}

CLI::App* addWhereCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* where = app.add_subcommand(
      "where", "Print the CDL source of a line of a compiled program, from its source map");
  where->add_option("PROGRAM", raw.whereProgram, "The program")->type_name("")->required();
  where->add_option("LINE", raw.whereLocation, "A line number, or a block number Nnnnn")
      ->type_name("")
      ->required();
  where
      ->add_option("--source-map", raw.sourceMap,
                   "The program's source map (default: PROGRAM.map.json)")
      ->type_name("FILE.json");
  where->footer("\nExit codes: 0 found, 1 the map or the line cannot be read or does not belong "
                "to the program, 2 wrong usage.");
  return where;
}

CLI::App* addLanguageServerCommand(CLI::App& app) {
  CLI::App* lsp = app.add_subcommand(
      "lsp", "Run the language server (Language Server Protocol on standard input and output)");
  lsp->add_flag_function(
      "--stdio", [](std::int64_t) {},
      "Use standard input and output (the default; editors pass it)");
  return lsp;
}

} // namespace cncc::driver
