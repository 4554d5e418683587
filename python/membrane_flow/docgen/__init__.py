"""Generators of the pages of docs/ that are made from runs or from the code: the parameter manual,
the experiments, the gallery, the parameter studies and the branches."""


def results_and_docs(argv, command, doc):
    """The arguments [results/studies] [docs] of a study-page generator, or None after printing
    the usage for -h/--help."""
    if argv[:1] in (['-h'], ['--help']):
        print(f'usage: python3 -m membrane_flow {command} [results/studies] [docs]\n\n' + doc)
        return None
    return (argv[0] if len(argv) > 0 else 'results/studies'), (argv[1] if len(argv) > 1 else 'docs')
