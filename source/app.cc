#include <membrane/app.h>
#include <membrane/parameters.h>
#include <membrane/simulator.h>

#include <deal.II/base/mpi.h>

#include <cctype>
#include <iostream>
#include <sstream>
#include <string>

namespace Membrane
{
  using namespace dealii;

  namespace
  {
    const char *usage = "Usage: membrane-flow [--quiet] [--set 'Section/Entry=value' ...] <input.prm>\n"
                        "       membrane-flow --print-parameters [prm|json]\n";

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
  } // namespace

  int run_application(int argc, char **argv)
  {
    const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    std::vector<std::string> args(argv + 1, argv + argc);
    RunOptions               options;
    for (int i = 0; i < argc; ++i)
      options.command_line += (i ? " " : "") + std::string(argv[i]);

    if (!args.empty() && args[0] == "--print-parameters")
      {
        ParameterHandler prm;
        Parameters::declare(prm);
        if (root)
          prm.print_parameters(std::cout, args.size() > 1 && args[1] == "json" ? ParameterHandler::JSON
                                                                                : ParameterHandler::PRM);
        return 0;
      }
    std::string                                      input;
    std::vector<std::pair<std::string, std::string>> overrides;
    for (std::size_t i = 0; i < args.size(); ++i)
      if (const std::string &a = args[i]; a == "--quiet")
        options.quiet = true;
      else if (a == "--set" && i + 1 < args.size() && args[i + 1].find('=') != std::string::npos)
        {
          const std::string &assignment = args[++i];
          const auto         eq         = assignment.find('=');
          overrides.emplace_back(assignment.substr(0, eq), assignment.substr(eq + 1));
        }
      else if (a == "--help" || a == "-h" || !input.empty() || a.rfind("--", 0) == 0)
        {
          if (root)
            std::cerr << usage;
          return a == "--help" || a == "-h" ? 0 : 1;
        }
      else
        input = a;
    if (input.empty())
      {
        if (root)
          std::cerr << usage;
        return 1;
      }

    ParameterHandler prm;
    Parameters       parameters;
    try
      {
        read_parameter_file(input, prm, parameters, overrides);
        std::ostringstream text;
        prm.print_parameters(text, ParameterHandler::ShortPRM);
        options.parameter_text = text.str();

        Simulator         simulator(parameters, options);
        return simulator.run().failed ? 2 : 0;
      }
    catch (const std::exception &e)
      {
        if (root)
          std::cerr << "Error: " << clean_message(e) << std::endl;
        return 1;
      }
  }
} // namespace Membrane
