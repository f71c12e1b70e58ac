"""Demo nodes, one per process: ``python -m console_tui.demo.nodes NAME``.

Each is a real rclpy node with logger services enabled. It exits when its stdin closes,
so the demo nodes never outlive the console that started them.
"""

from __future__ import annotations

import os
import sys
import threading

from .behaviours import DEMO_NODES


def run(name: str) -> int:
    import rclpy
    from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
    from rclpy.node import Node

    node_name, namespace, set_up = DEMO_NODES[name]
    rclpy.init()
    node = Node(node_name, namespace=namespace, enable_logger_service=True)
    set_up(node.get_logger(), node.create_timer)
    executor = SingleThreadedExecutor()
    executor.add_node(node)

    def exit_when_parent_goes() -> None:
        sys.stdin.read()
        rclpy.try_shutdown()

    threading.Thread(target=exit_when_parent_goes, daemon=True).start()
    try:
        executor.spin()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        executor.shutdown(timeout_sec=0)
        node.destroy_node()
        rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2 or sys.argv[1] not in DEMO_NODES:
        print(f"usage: python -m console_tui.demo.nodes {{{','.join(DEMO_NODES)}}}", file=sys.stderr)
        raise SystemExit(2)
    code = run(sys.argv[1])
    # rclpy is shut down by now; the interpreter's own ending (Fast DDS's static
    # destructors) took another 0.5 s or more, and the console waits for its demo nodes.
    sys.stderr.flush()
    os._exit(code)
