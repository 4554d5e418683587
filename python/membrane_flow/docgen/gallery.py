"""Render the gallery docs/gallery.md: one picture per figure of the paper (Figs. 7.1-7.4)
and one of the closed vesicles, made from the runs of scripts/run_experiments.sh in results/. Each panel is a snapshot of a
run coloured by phi, rendered with VTK (membrane_flow/pictures/render.py); energy panels come from
the statistics.

Usage (from the repository's top directory): python3 -m membrane_flow gallery [results-dir] [docs-dir]
A figure whose runs are not all in results-dir keeps its section (and picture) of the existing page."""
import os
import sys

import matplotlib


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] in (['-h'], ['--help']):
        print('usage: python3 -m membrane_flow gallery [results-dir] [docs-dir]\n\n' + __doc__)
        return 0
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    import numpy as np

    from vtkmodules.util.numpy_support import vtk_to_numpy

    from membrane_flow.pictures.render import SurfaceRenderer, read_vtu, surface_polydata
    from membrane_flow.run import load_statistics
    from membrane_flow.workflow.experiment_runs import command

    results = argv[0] if len(argv) > 0 else 'results'
    docs = argv[1] if len(argv) > 1 else 'docs'
    images = os.path.join(docs, 'images', 'gallery')
    os.makedirs(images, exist_ok=True)

    # figure id, caption, panels: (run, time or None for the last snapshot, title, elevation);
    # ('energy', [runs]) draws the energy curves of runs.
    FIGURES = [
        ('7.1', 'Sorting on a slightly curved patch: the disordered mixture (A) separates into domains of the '
         'minority phase A (red) that bulge out (B, C); the energy decays (D).',
         [('7.1-sorting-patch', 0.0, 'A: t = 0', 35), ('7.1-sorting-patch', 0.2, 'B: t = 0.2', 35),
          ('7.1-sorting-patch', None, 'C: end', 35), ('energy', ['7.1-sorting-patch'])]),
        ('7.2', 'Linear (A) and tanh (B) laws kappa(phi), kappa(-1) = 3, kappa(1) = 1, from the same initial '
         'mixture: different patterns and energy curves (C).',
         [('7.2-kappa-linear', None, 'A: linear, end', 35), ('7.2-kappa-tanh', None, 'B: tanh, end', 35),
          ('energy', ['7.2-kappa-linear', '7.2-kappa-tanh'])]),
        ('7.3', 'A bud grows from the centred phase-A domain (sigma = 90): t = 0 (A), 0.2 (B), 3.1 (C).',
         [('7.3-budding', 0.0, 'A: t = 0', 20), ('7.3-budding', 0.2, 'B: t = 0.2', 20),
          ('7.3-budding', None, 'C: t = 3.1', 20)]),
        ('7.4', 'Line tension and domain size: sigma = 90 (A), 540 (B), 630 (C), 1000 (C\', above the critical '
         'value of this discretization), the smaller domain at 630 (D) and 1000 (D\'), and H0_A = +5 budding to the '
         'other side (E).',
         [('7.4A-sigma90', None, 'A: sigma 90', 15), ('7.4B-sigma540', None, 'B: sigma 540', 15),
          ('7.4C-sigma630', None, 'C: sigma 630', 15), ('7.4C-sigma1000', None, "C': sigma 1000", 10),
          ('7.4D-small-domain', None, 'D: small domain', 15), ('7.4D-sigma1000', None, "D': small domain, sigma 1000", 15), ('7.4E-opposite-side', None, 'E: H0_A = +5', 10)]),
        ('Closed vesicles', 'Beyond the paper ([vesicles.md](vesicles.md)): a homogeneous vesicle relaxed to the prolate '
         'equilibrium at reduced volume 0.9 (A); a cap domain of 30 % of the area at the tip of a prolate vesicle '
         '(B) that buds out on a neck as the vesicle is deflated to v = 0.7 (C); a random mixture with H0_A = -2 (D) sorted into '
         'outward-bulging phase-A domains (E); a domain of 10 % of the area at v = 0.85 that stays a dome at '
         'line tension sigma = 10 (F) and buds out at sigma = 200 (G); the energies of the phase-field runs decay (H; '
         'for the deflated vesicles F less the work p dV of the volume target).',
         [('vesicle-prolate', None, 'A: prolate, v = 0.9', 20), ('vesicle-domain-budding', 0.0, 'B: cap, t = 0', 20),
          ('vesicle-domain-budding', None, 'C: cap, end', 20), ('vesicle-sorting', 0.0, 'D: mixture, t = 0', 20),
          ('vesicle-sorting', None, 'E: sorted, end', 20), ('vesicle-small-domain-sigma10', None, 'F: 10 %, sigma 10', 20),
          ('vesicle-small-domain', None, 'G: 10 %, sigma 200', 20),
          ('energy', ['vesicle-domain-budding', 'vesicle-sorting', 'vesicle-small-domain-sigma10', 'vesicle-small-domain'])]),
    ]

    lines = ['# Gallery: the paper\'s figures 7.1-7.4 and closed vesicles\n',
             'Each picture is made from the full runs of the experiments (`experiments/`, see',
             '[experiments.md](experiments.md)); red is phase A (phi = +1), blue phase B. To regenerate all:\n',
             '```sh\nscripts/run_experiments.sh            # the runs, into results/ (~35 min)',
             '/usr/bin/python3 -m membrane_flow gallery results docs   # this page\n```\n']


    def previous_sections(path):
        """{heading: text} of the '## ' sections of an existing gallery page, kept for figures whose
        runs are not in results/ (so that one figure can be regenerated from its own runs)."""
        sections, heading = {}, None
        if os.path.exists(path):
            with open(path) as f:
                for line in f:
                    if line.startswith('## '):
                        heading = line[3:].strip()
                        sections[heading] = ''
                    if heading is not None:
                        sections[heading] += line
        return sections


    kept = previous_sections(os.path.join(docs, 'gallery.md'))
    for figure, caption, panels in FIGURES:
        runs = sorted({p[0] for p in panels if p[0] != 'energy'} |
                      {r for p in panels if p[0] == 'energy' for r in p[1]})
        heading = f'Fig. {figure}' if figure[0].isdigit() else figure
        if not all(os.path.exists(os.path.join(results, r, 'surface.pvd')) for r in runs):
            if heading in kept:
                print(f'{heading}: missing runs in {results}, the previous section and picture are kept')
                lines.append(kept[heading].rstrip('\n') + '\n')
            else:
                print(f'skipping {figure}: missing runs in {results}')
            continue
        columns = len(panels) if len(panels) <= 4 else 4
        rows = (len(panels) + columns - 1) // columns
        fig = plt.figure(figsize=(4.2 * columns + 0.6, 3.6 * rows), dpi=100)
        grid = fig.add_gridspec(rows, columns + 1, width_ratios=[1] * columns + [0.06])
        # the snapshots of one run share a frame, so that their sizes compare
        surfaces = {k: read_vtu(os.path.join(results, p[0], 'surface.pvd'), p[1])
                    for k, p in enumerate(panels) if p[0] != 'energy'}
        frames = {}
        for k, surface in surfaces.items():
            points = vtk_to_numpy(surface.GetPoints().GetData())
            frames[panels[k][0]] = np.concatenate([frames.get(panels[k][0], np.empty((0, 3))), points])
        for k, panel in enumerate(panels):
            ax = fig.add_subplot(grid[k // columns, k % columns])
            if panel[0] == 'energy':
                for run in panel[1]:
                    s = load_statistics(os.path.join(results, run))
                    # a deflating vesicle: the work p dV of the volume target is taken out (the
                    # functional the flow decreases)
                    work = 'pressure_work' in s and np.abs(s['pressure_work']).max() > 1e-6 * np.abs(s['energy']).max()
                    ax.plot(s['time'], s['energy'] - (s['pressure_work'] if work else 0),
                            label=run + (' (F - work p dV)' if work else ''))
                ax.set(xlabel='t', ylabel='free energy F', title=f'{chr(65 + k)}: energy')
                ax.set_yscale('log')
                ax.legend(fontsize=7)
                ax.grid(alpha=0.3)
                continue
            run, time, title, elev = panel
            surface = surfaces[k]
            renderer = SurfaceRenderer((840, 720), views=[(elev, -60)], colorbar=False, timestamp=False)
            renderer.set_surface(surface_polydata(surface))
            renderer.frame_to(frames[run])
            ax.imshow(renderer.image(), interpolation='antialiased')
            if 't =' not in title and surface.snapshot_time is not None:
                title += f' (t = {surface.snapshot_time:.3g})'
            ax.set_title(title, fontsize=10)
            ax.set_axis_off()
        # one colour bar for the phi panels
        bar = fig.add_subplot(grid[0, columns])
        fig.colorbar(plt.cm.ScalarMappable(cmap='coolwarm', norm=plt.Normalize(-1, 1)), cax=bar, label='phi',
                     ticks=np.linspace(-1, 1, 5))
        fig.tight_layout()
        paper_figure = figure[0].isdigit()
        name = f'fig{figure}.png' if paper_figure else figure.lower().replace(' ', '-') + '.png'
        fig.savefig(os.path.join(images, name + '.partial.png'))
        plt.close(fig)
        os.replace(os.path.join(images, name + '.partial.png'), os.path.join(images, name))
        commands = '\n'.join(command(r) for r in runs)
        lines += [f'## {heading}\n', caption + '\n', f'![{heading}](images/gallery/{name})\n',
                  f'Runs:\n\n```sh\n{commands}\n```\n']
        print(f'{heading}: {name}')
    with open(os.path.join(docs, 'gallery.md'), 'w') as f:
        f.write('\n'.join(lines))
    return 0


if __name__ == '__main__':
    sys.exit(main())
