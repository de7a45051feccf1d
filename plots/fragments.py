"""Fragment velocities: at each fragment block time, every fragment as a bar from its top
to its bottom face at the height of its mean velocity.

usage: fragments.py PREFIX -o fragments.png

Without fragment blocks (they come with the profiles: &run profile_times), or when the bar
is one piece in every block (it never broke), the figure is still written, with the line
'fragments.py: warning: nothing to draw: ...' on stderr; the exit status stays 0.
"""
from _common import nothing_to_draw, parser, plt, save, spbread


def plot(run, ax):
    if not run.fragments:
        nothing_to_draw("no fragment blocks (they come with the profiles: &run profile_times)")
    elif all(len(b["id"]) <= 1 for b in run.fragments):
        nothing_to_draw(f"no fragments: the bar is one piece in all {len(run.fragments)} "
                        "fragment blocks")
    cmap = plt.get_cmap("plasma")
    n = max(1, len(run.fragments) - 1)
    for k, b in enumerate(run.fragments):
        c = cmap(k / n)
        for j in range(len(b["id"])):
            ax.plot([b["x_top"][j], b["x_bottom"][j]], [b["velocity"][j]] * 2, color=c, lw=2)
        ax.plot([], [], color=c, lw=2, label=f"t = {b['t'] * 1e3:.4g} ms, {len(b['id'])} "
                f"{'piece' if len(b['id']) == 1 else 'pieces'}")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("position x + u [m]")
    ax.set_ylabel("mean velocity [m/s] (down > 0)")
    if run.fragments:
        ax.legend(fontsize=7)


def main():
    args = parser(__doc__).parse_args()
    run = spbread.load(args.prefix[0])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    plot(run, ax)
    ax.set_title(args.title or run.title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
