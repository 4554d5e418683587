"""The command line of membrane_flow: python3 -m membrane_flow [--exe PATH] <command> [options].

`python3 -m membrane_flow --help` lists the commands, `python3 -m membrane_flow <command> --help`
the options of one. The option before the command is shared by all of them:

  --exe PATH   the membrane-flow program every command runs (sets MEMBRANE_FLOW_EXE); default:
               the program of the build this package belongs to, else `membrane-flow` on PATH
               (membrane_flow.launch.find_executable). A command's own --exe overrides it.
"""
import importlib
import os
import sys

# command -> (module, one line of help); the module's main(argv) runs the command and returns its exit code.
COMMANDS = {
    # the workflow (docs/workflow.md)
    'sweep': ('workflow.sweep', 'run a parameter sweep from a sweep file into one results table'),
    'critical': ('workflow.critical', 'bisect one parameter for the change of outcome class'),
    'continuation': ('workflow.continuation',
                     'follow a branch of equilibria in one parameter (follow), or compare two (compare)'),
    'budding-time': ('workflow.budding_time', 'the budding time T_min of finished runs'),
    # pictures (docs/visualization.md)
    'render': ('pictures.render', 'PNG of a surface (a VTU, or a snapshot of a PVD series) with VTK'),
    'movie': ('pictures.movie', 'MP4 of every snapshot of a run'),
    'plot-history': ('pictures.history', 'energy, conservation and bud observables of runs against time'),
    'plot-study': ('pictures.study', 'an observable of a sweep against the varied parameter'),
    # studies
    'mesh-convergence': ('studies.mesh_convergence', 'the mesh-convergence study (docs/mesh-convergence.md)'),
    'neck-resolution': ('studies.neck_resolution', 'the neck-resolution study (docs/neck-resolution*.md)'),
    'time-step-study': ('studies.time_steps', 'the time-step accuracy study (docs/time-step-accuracy.md)'),
    'study-7.1': ('studies.sorting_7_1', 'experiment 7.1 with one change at a time (docs/experiments.md)'),
    'axisymmetric-vesicle': ('studies.axisymmetric_vesicle',
                             'reference shapes of revolution (sphere, spheroid, prolate branch)'),
    'spectrum': ('spectra', 'a thermal run\'s stationary height or shape spectrum against equilibrium'),
    'capillary': ('capillary', 'the capillary-wave spectrum of a phase boundary against the line tension'),
    'sharp-interface': ('sharp_interface',
                        'the sharp-interface limit of 7.3 (experiments/studies/sharp_interface)'),
    # the generated pages of docs/
    'parameter-manual': ('docgen.parameter_manual', 'docs/parameters.md from the declarations in the code'),
    'experiment-docs': ('docgen.experiments', 'docs/experiments.md from the runs of the experiments'),
    'gallery': ('docgen.gallery', 'docs/gallery.md: the paper\'s figures from the experiment runs'),
    'study-docs': ('docgen.studies', 'docs/studies.md from the sweeps and bisections'),
    'branch-docs': ('docgen.branches', 'docs/branches.md from the continuation runs'),
}
PROG = 'python3 -m membrane_flow'


def usage(commands):
    width = max(len(name) for name in commands)
    lines = [f'usage: {PROG} [--exe PATH] <command> [options]   ({PROG} <command> --help for its options)', '',
             'commands:']
    lines += [f'  {name:{width}s}  {text}' for name, (_, text) in commands.items()]
    lines += ['', 'shared option (before the command):',
              '  --exe PATH  the membrane-flow program every command runs (else the build of this package, '
              'else membrane-flow on PATH)']
    return '\n'.join(lines)


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    commands = COMMANDS
    while argv and argv[0].startswith('-'):
        option = argv.pop(0)
        if option in ('-h', '--help'):
            print(usage(commands))
            return 0
        if option == '--exe' and argv or option.startswith('--exe='):
            exe = argv.pop(0) if option == '--exe' else option.split('=', 1)[1]
            # a path (made absolute: some commands run from another directory), or a name on PATH
            os.environ['MEMBRANE_FLOW_EXE'] = os.path.abspath(exe) if os.sep in exe or os.path.exists(exe) else exe
        else:
            print(usage(commands), file=sys.stderr)
            print(f'{PROG}: error: unknown option {option}', file=sys.stderr)
            return 2
    if not argv:
        print(usage(commands), file=sys.stderr)
        print(f'{PROG}: error: give a command', file=sys.stderr)
        return 2
    name, args = argv[0], argv[1:]
    if name not in commands:
        import difflib
        close = difflib.get_close_matches(name, commands, n=1)
        print(usage(commands), file=sys.stderr)
        print(f'{PROG}: error: unknown command {name!r}' + (f' (did you mean {close[0]!r}?)' if close else ''),
              file=sys.stderr)
        return 2
    module = commands[name][0]
    sys.argv = [f'membrane_flow {name}'] + args  # the program name in usage and error messages
    code = importlib.import_module(f'{__package__}.{module}').main(args)
    return code if code is not None else 0


if __name__ == '__main__':
    sys.exit(main())
