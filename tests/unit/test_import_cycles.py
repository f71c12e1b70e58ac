"""No module of ``console_tui`` imports, directly or through others, a module that imports it.

The import graph is grimp's (import-linter's own). Imports made only for type checking
(``if TYPE_CHECKING:``) count: a circle through annotations still means neither module can be
read, moved or tested without the other. A part that needs its whole (a mixin, a provider)
names what it needs in a ``Protocol`` instead.
"""

from __future__ import annotations

from graphlib import CycleError, TopologicalSorter

import grimp


def test_no_import_circles():
    graph = grimp.build_graph("console_tui", exclude_type_checking_imports=False, cache_dir=None)
    order = TopologicalSorter({module: graph.find_modules_directly_imported_by(module) for module in graph.modules})
    try:
        order.prepare()
    except CycleError as error:
        circle = error.args[1]
        raise AssertionError(f"modules import each other in a circle: {' -> '.join(circle)}") from None
