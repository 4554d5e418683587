"""Branch continuation in one parameter: follow an equilibrium as the parameter moves.

A bistable system (a flat or incomplete bud and a complete bud, over a range of line
tensions) has two branches of equilibria. Each is followed by continuation: relax at
the first value from a start state, then move the parameter one step and relax again
*from the previous equilibrium*, until the state leaves the branch (its class changes:
the bud reopens, or the domain buds) or the values run out.

`follow_branch(relax, values, state)` needs relax(value, state) -> dict with at least
'state' (what the next relaxation starts from), 'energy' and 'class'. The branch is the
class of the first relaxation; the first result of another class ends it and is kept
as `left_at`.

From two branches followed towards each other:
- `turning_point(branch)`: the bracket [last value on the branch, first value off it]
  where the branch ends (a saddle-node: the state it was in stops existing);
- `crossing(a, b)`: where the energies of the two branches are equal (linear
  interpolation of E_a - E_b between the values both branches hold), the thermodynamic
  threshold; None if they do not cross where both exist.
"""


def follow_branch(relax, values, state):
    points, left_at, branch = [], None, None
    for value in values:
        result = dict(relax(value, state))
        result['value'] = value
        if branch is None:
            branch = result['class']
        if result['class'] != branch:
            left_at = result
            break
        points.append(result)
        state = result['state']
    return {'class': branch, 'points': points, 'left_at': left_at}


def turning_point(branch):
    """[last value on the branch, first value off it], or None if it never left."""
    if branch['left_at'] is None or not branch['points']:
        return None
    return [branch['points'][-1]['value'], branch['left_at']['value']]


def crossing(a, b):
    """The parameter where the two branches' energies are equal, or None."""
    energy_b = {p['value']: p['energy'] for p in b['points']}
    common = sorted(v for v in (p['value'] for p in a['points']) if v in energy_b)
    energy_a = {p['value']: p['energy'] for p in a['points']}
    difference = [(v, energy_a[v] - energy_b[v]) for v in common]
    for (v0, d0), (v1, d1) in zip(difference, difference[1:]):
        if d0 == 0:
            return v0
        if d0 * d1 < 0:
            return v0 + (v1 - v0) * d0 / (d0 - d1)
    if difference and difference[-1][1] == 0:
        return difference[-1][0]
    return None
