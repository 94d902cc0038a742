"""What the benchmarks' plots share: panels finished alike and saved as PNG."""


def save_panels(fig, axes, path):
    """Grid and legend on each panel, tight layout, PNG at 110 dpi."""
    for a in axes:
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
