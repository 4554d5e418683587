"""Write docs/experiments.md and its pictures from finished experiment runs.

For each experiment in EXPERIMENTS whose results/<name>/summary.json exists:
a picture of the final surface coloured by phi, the history plot (energy,
conservation, bud observables), and a table row with the measured outcome.
The page starts with experiments_header.md (next to this file).
Usage (after scripts/run_experiments.sh; from the repository's top directory):
  python3 -m membrane_flow experiment-docs [results-dir] [docs-dir]"""
import os
import sys

from membrane_flow.pictures import history, render
from membrane_flow.run import load_summary
from membrane_flow.workflow.experiment_runs import command


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] in (['-h'], ['--help']):
        print('usage: python3 -m membrane_flow experiment-docs [results-dir] [docs-dir]\n\n' + __doc__)
        return 0
    HERE = os.path.dirname(os.path.abspath(__file__))
    results = argv[0] if len(argv) > 0 else 'results'
    docs = argv[1] if len(argv) > 1 else 'docs'
    images = os.path.join(docs, 'images', 'experiments')
    os.makedirs(images, exist_ok=True)

    # name, what the paper reports, camera elevation
    EXPERIMENTS = [
        ('7.1-sorting-patch', 'the mixture sorts into a single domain of the minority phase, which buds; energy decays', 35),
        ('7.2-kappa-linear', 'linear kappa(phi): a sorting pattern different from the tanh law', 35),
        ('7.2-kappa-tanh', 'tanh kappa(phi): a sorting pattern different from the linear law', 35),
        ('7.3-budding', 'a single bud grows from the centred domain, near equilibrium at t = 3.1', 20),
        ('7.4A-sigma90', 'incomplete bud (sigma = 90)', 20),
        ('7.4B-sigma540', 'more budded, still incomplete (sigma = 540)', 20),
        ('7.4C-sigma630', 'complete bud (sigma = 630)', 15),
        ('7.4C-sigma1000', '(not in the paper) the 7.4 C setup above the critical sigma of this discretization', 10),
        ('7.4D-small-domain', 'the smaller domain does not bud where the larger one (7.4 C) does', 20),
        ('7.4D-sigma1000', '(not in the paper) the smaller domain at sigma = 1000, where the larger one (7.4 C\') protrudes like a sphere', 15),
        ('7.4E-opposite-side', 'the bud forms on the side opposite to the initial bump', 10),
    ]

    rows, sections = [], []
    for name, paper, elev in EXPERIMENTS:
        run = os.path.join(results, name)
        summary_path = os.path.join(run, 'summary.json')
        if not os.path.exists(summary_path):
            print(f'skipping {name}: no {summary_path}')
            continue
        s = load_summary(run)
        shape_png, history_png = f'{name}.png', f'{name}-history.png'
        render.main([os.path.join(run, 'surface.pvd'), os.path.join(images, shape_png), '--size', '640x480',
                     '--elev', str(elev)])
        history.main([run, '-o', os.path.join(images, history_png), '--title', name])
        direction = 'up' if s['bud_direction'] > 0 else 'down'
        rows.append(f"| {name} | {paper} | **{s['outcome']}** ({direction}) | {s['time']:.3g} | {s['steps']} "
                    f"({s['rejected_steps']}) | {s['energy']:.4g} | {s['bud_height']:.3f} | {s['neck_radius']:.3f} | "
                    f"{s['domain_protrusion']:.2f} | {s['area_drift']:.1e} | {s['mass_drift']:.1e} | "
                    f"{s['wall_seconds']:.0f} s |")
        sections.append(f"### {name}\n\nPaper: {paper}. Here: **{s['outcome']}**, stopped by "
                        f"\"{s['stop_reason']}\".\n\n```sh\n{command(name)}\n```\n\n"
                        f"![{name} final shape](images/experiments/{shape_png})\n"
                        f"![{name} history](images/experiments/{history_png})\n")

    with open(os.path.join(HERE, 'experiments_header.md')) as f:
        header = f.read()
    table = ('| run | paper | outcome here (bud side) | t end | steps (rejected) | F end | bud height | neck radius | '
             'protrusion | area drift | mass drift | wall |\n|' + '---|' * 12 + '\n' + '\n'.join(rows) + '\n')
    with open(os.path.join(docs, 'experiments.md'), 'w') as f:
        f.write(header + '\n## Results\n\n' + table + '\n' + '\n'.join(sections))
    print(f"wrote {os.path.join(docs, 'experiments.md')} with {len(rows)} experiments")
    return 0


if __name__ == '__main__':
    sys.exit(main())
