"""The runs shown in docs/experiments.md and docs/gallery.md and the command that makes each:
an input file of experiments/, or a variation of one (scripts/run_experiments.sh runs them all)."""

# name -> (input file it varies, the override)
VARIANTS = {
    '7.4C-sigma1000': ('7.4C-sigma630', 'Material/Line tension=1000'),
    '7.4D-sigma1000': ('7.4D-small-domain', 'Material/Line tension=1000'),
    'vesicle-small-domain-sigma10': ('vesicle-small-domain', 'Material/Line tension=10'),
}


def command(name):
    if name in VARIANTS:
        base, setting = VARIANTS[name]
        return (f"membrane-flow --set '{setting}' --set 'Output/Directory=results/{name}' "
                f"experiments/{base}.prm")
    return f'membrane-flow experiments/{name}.prm'
