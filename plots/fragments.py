"""Fragment velocities: at each fragment block time, every fragment as a bar from its top
to its bottom face at the height of its mean velocity.

usage: fragments.py PREFIX [--t-min T] [--t-max T] [--units us] -o fragments.png

--t-min/--t-max keep the blocks whose times lie between them; the legend gives the times in
ms unless --units says otherwise (the options: doc/outputs.md, "Plots"). Without fragment
blocks (they come with the profiles: &run profile_times; or none in the time window), or
when the bar is one piece in every block (it never broke), the figure is still written,
with the line 'fragments.py: warning: nothing to draw: ...' on stderr; the exit status
stays 0.
"""
from _common import View, load, nothing_to_draw, parse, parser, plt, save


def plot(run, ax, view=None):
    view = view or View()
    blocks = [b for b in run.fragments if view.keep(b["t"])]
    if not run.fragments:
        nothing_to_draw("no fragment blocks (they come with the profiles: &run profile_times)")
    elif not blocks:
        nothing_to_draw(f"none of the {len(run.fragments)} fragment blocks in the time window")
    elif all(len(b["id"]) <= 1 for b in blocks):
        nothing_to_draw(f"no fragments: the bar is one piece in all {len(blocks)} "
                        "fragment blocks")
    cmap = plt.get_cmap("plasma")
    n = max(1, len(blocks) - 1)
    for k, b in enumerate(blocks):
        c = cmap(k / n)
        for j in range(len(b["id"])):
            ax.plot([b["x_top"][j], b["x_bottom"][j]], [b["velocity"][j]] * 2, color=c, lw=2)
        ax.plot([], [], color=c, lw=2, label=f"t = {view.t(b['t']):.4g} {view.time_unit}, "
                f"{len(b['id'])} {'piece' if len(b['id']) == 1 else 'pieces'}")
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_xlabel("position x + u [m]")
    ax.set_ylabel("mean velocity [m/s] (down > 0)")
    if blocks:
        ax.legend(fontsize=7)


def main():
    args = parse(parser(__doc__))
    run = load(args.prefix[0])
    fig, ax = plt.subplots(figsize=(8, 4.5))
    plot(run, ax, args.view)
    ax.set_title(args.title or run.title, fontsize=9)
    save(fig, args.output)


if __name__ == "__main__":
    main()
