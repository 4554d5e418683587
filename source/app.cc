#include <membrane/app.h>
#include <membrane/io/memory.h>
#include <membrane/io/run_directory.h>
#include <membrane/io/stop_signal.h>
#include <membrane/parameters.h>
#include <membrane/simulator.h>
#include <membrane/core/types.h>

#include <deal.II/base/mpi.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include <unistd.h>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    const char *usage =
      "Usage: membrane-flow [--quiet] [--overwrite] [--no-memory-check] [--set 'Section/Entry=value' ...] <input.prm>\n"
      "       membrane-flow --print-parameters [prm|json]\n"
      "       membrane-flow --version | --help\n"
      "  --set 'Section/Entry=value'  override an entry of the input file (repeatable)\n"
      "  --quiet                      no progress lines and no timing table\n"
      "  --overwrite                  delete the output files of an earlier run in Output/Directory first\n"
      "                               (only files membrane-flow writes; see docs/reliability.md)\n"
      "  --no-memory-check            start even if the memory estimate exceeds the available memory\n"
      "Exit codes: 0 success, 1 bad input or usage, 2 the run failed numerically,\n"
      "            128 + signal when stopped by SIGINT (130) or SIGTERM (143).\n";

    /// A usage error: a message naming the problem, then a pointer to --help.
    struct UsageError : std::runtime_error
    {
      using std::runtime_error::runtime_error;
    };

    /// Collapse runs of whitespace (deal.II wraps its messages) into one space.
    std::string single_line(const std::string &text)
    {
      std::string out;
      for (const char c : text)
        if (!std::isspace(static_cast<unsigned char>(c)))
          out += c;
        else if (!out.empty() && out.back() != ' ')
          out += ' ';
      while (!out.empty() && (out.back() == ' ' || out.back() == '-'))
        out.pop_back();
      return out;
    }

    /// The user-facing part of a deal.II exception text.
    std::string clean_message(const std::exception &e)
    {
      const std::string text = e.what();
      for (const std::string marker : {"Additional information: \n", "Additional information:\n"})
        if (const auto pos = text.find(marker); pos != std::string::npos)
          {
            std::string info = text.substr(pos + marker.size());
            if (const auto end = info.find("\n\nStacktrace"); end != std::string::npos)
              info = info.substr(0, end);
            return single_line(info);
          }
      return single_line(text);
    }

    struct CommandLine
    {
      RunOptions                                       options;
      std::string                                      input;
      std::vector<std::pair<std::string, std::string>> overrides;
      bool                                             overwrite       = false;
      bool                                             check_memory    = true;
    };

    /// Every argument is checked: a malformed --set, an unknown option or a second input
    /// file is a UsageError (never ignored, never a default run).
    CommandLine parse_command_line(const std::vector<std::string> &args)
    {
      CommandLine line;
      const auto  add_override = [&](const std::string &assignment) {
        const auto eq = assignment.find('=');
        if (eq == std::string::npos)
          throw UsageError("--set " + assignment + ": expected 'Section/Entry=value' (there is no '='), e.g. --set "
                                                   "'Material/Line tension=630'");
        if (assignment.find_first_not_of(" \t", 0) >= eq)
          throw UsageError("--set " + assignment + ": the entry path before '=' is empty; expected "
                                                   "'Section/Entry=value', e.g. --set 'Material/Line tension=630'");
        line.overrides.emplace_back(assignment.substr(0, eq), assignment.substr(eq + 1));
      };
      for (std::size_t i = 0; i < args.size(); ++i)
        {
          const std::string &a = args[i];
          if (a == "--quiet")
            line.options.quiet = true;
          else if (a == "--overwrite")
            line.overwrite = true;
          else if (a == "--no-memory-check")
            line.check_memory = line.options.check_memory = false;
          else if (a == "--set")
            {
              if (i + 1 >= args.size())
                throw UsageError("--set needs an argument 'Section/Entry=value', e.g. --set 'Material/Line tension=630'");
              add_override(args[++i]);
            }
          else if (a.rfind("--set=", 0) == 0)
            add_override(a.substr(6));
          else if (a == "--print-parameters" || a == "--version" || a == "--help" || a == "-h")
            throw UsageError(a + " must come alone (first) on the command line");
          else if (a.size() > 1 && a[0] == '-')
            throw UsageError("unknown option <" + a + ">");
          else if (!line.input.empty())
            throw UsageError("more than one input file: <" + line.input + "> and <" + a +
                             "> (one input file; quote values with spaces: --set 'Section/Entry=a b')");
          else
            line.input = a;
        }
      if (line.input.empty())
        throw UsageError("no input file given");
      return line;
    }

    /// Refuse a mesh far too large for the machine(s), before anything is allocated.
    void check_memory(const Parameters &parameters, const MPI_Comm communicator)
    {
      const unsigned int   ranks     = Utilities::MPI::n_mpi_processes(communicator);
      const double         available = available_memory(communicator);
      const MemoryEstimate estimate  = estimate_memory(parameters, ranks);
      if (available < 0)
        return;
      if (estimate.bytes <= available)
        {
          // Local refinement: the mesh refined everywhere is the worst case. The run
          // refines only where the indicators ask, and refuses a refinement that would
          // not fit (Simulator::adapt_mesh), so this is a note, not a refusal.
          const unsigned int level = parameters.adaptivity.max_level;
          const double       everywhere =
            level > 0 && level < 16 ? estimate_memory(parameters, ranks, parameters.cells_per_side << level).bytes : 0;
          if (everywhere > available && Utilities::MPI::this_mpi_process(communicator) == 0)
            std::cout << "Note: <Mesh/Maximum refinement level> = " << level << ": refined everywhere, the mesh would "
                      << "need an estimated " << format_bytes(everywhere) << " of memory, and "
                      << format_bytes(available) << " is available. The run refines only where the interface and "
                      << "the curvature ask for it, and does not refine further when a refinement would not fit in "
                      << "the available memory (it says so)." << std::endl;
          return;
        }
      unsigned int fits = 0;
      for (unsigned int n = 2; n <= parameters.cells_per_side; ++n)
        if (estimate_memory(parameters, ranks, n).bytes <= available)
          fits = n;
      std::ostringstream message;
      message << "Entry <Mesh/Cells per side> = " << parameters.cells_per_side << ": the run needs an estimated "
              << format_bytes(estimate.bytes) << " of memory (" << std::setprecision(3) << estimate.vertices / 1e6
              << " million vertices; "
              << (parameters.linear_solver.type == "direct" ? "the direct solver's LU factors dominate"
                                                            : "GMRES matrices and vectors")
              << "; formula in docs/reliability.md), but only " << format_bytes(available)
              << " is available (MemAvailable in /proc/meminfo" << (ranks > 1 ? ", summed over the hosts" : "")
              << "). Reduce <Mesh/Cells per side>"
              << (fits >= 2 ? " (at most " + std::to_string(fits) + " fits here)" : std::string())
              << ", run on more machines with mpirun, or skip this check with --no-memory-check";
      AssertThrow(false, ExcMessage(message.str()));
    }

    /// Errors go last: after the simulator (and its timer) is gone and stdout is flushed.
    void print_error(const bool root, const std::string &message)
    {
      if (!root)
        return;
      std::cout.flush();
      std::fflush(stdout);
      std::cerr << "Error: " << message << std::endl;
    }
  } // namespace

  std::string error_message(const std::exception &e)
  {
    return clean_message(e);
  }

  int run_application(int argc, char **argv)
  {
    const bool               root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    std::vector<std::string> args(argv + 1, argv + argc);

    if (!args.empty() && args[0] == "--print-parameters")
      {
        const std::string format = args.size() > 1 ? args[1] : "prm";
        if (args.size() > 2 || (format != "prm" && format != "json"))
          {
            print_error(root, "--print-parameters takes one optional format, prm or json (got <" +
                                (args.size() > 2 ? args[2] : format) + ">)");
            return 1;
          }
        ParameterHandler prm;
        Parameters::declare(prm);
        if (root)
          prm.print_parameters(std::cout, format == "json" ? ParameterHandler::JSON : ParameterHandler::PRM);
        return 0;
      }
    if (args.size() == 1 && args[0] == "--version")
      {
        if (root)
          std::cout << "membrane-flow " << code_version() << std::endl;
        return 0;
      }
    if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h"))
      {
        if (root)
          std::cout << usage;
        return 0;
      }

    CommandLine line;
    try
      {
        line = parse_command_line(args);
      }
    catch (const UsageError &e)
      {
        print_error(root, std::string(e.what()) + " (membrane-flow --help for the usage)");
        return 1;
      }
    for (int i = 0; i < argc; ++i)
      line.options.command_line += (i ? " " : "") + std::string(argv[i]);

    install_stop_signal_handlers();

    // The simulator lives in this scope only: an error is caught while it still exists and
    // printed after it is destroyed, so that nothing (its timer, deal.II's notes about
    // destructors during an exception) comes after the message.
    std::string error;
    int         code = 0;
    {
      RunDirectory               directory; // holds the directory's lock until the run is over
      std::unique_ptr<Simulator> simulator;
      try
        {
          ParameterHandler prm;
          Parameters       parameters;
          read_parameter_file(line.input, prm, parameters, line.overrides);
          std::ostringstream text;
          prm.print_parameters(text, ParameterHandler::ShortPRM);
          line.options.parameter_text = text.str();

          if (line.check_memory)
            check_memory(parameters, MPI_COMM_WORLD);
          directory = claim_run_directory({parameters.output_directory, line.overwrite, parameters.resume_from,
                                           {line.input}},
                                          MPI_COMM_WORLD);
          if (root && !directory.note().empty())
            std::cout << directory.note() << std::endl;

          simulator              = std::make_unique<Simulator>(parameters, line.options);
          const RunResult result = simulator->run();
          if (const int signal = stop_signal(); signal != 0)
            {
              code  = 128 + signal;
              error = std::string("stopped by ") + stop_signal_name(signal) + " (" + result.stop_reason + ")";
            }
          else if (result.failed)
            {
              code  = 2;
              error = "the run failed: " + result.stop_reason;
            }
        }
      catch (const std::exception &e)
        {
          error = clean_message(e);
          code  = 1;
        }
      simulator.reset();
    }
    if (!error.empty())
      print_error(root, error);
    return code;
  }
} // namespace Membrane
