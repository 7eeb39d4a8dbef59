"""An rclpy node spun on its own executor thread: the peer of the ROS tests (helpers.Peer builds
on it) and of the benchmarks (benches/*.py and scripts/bench_flood.py put this directory on
sys.path). rclpy.init() must have been called."""

import threading

import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.parameter import Parameter


class SpunNode:
    """An rclpy node (`self.node`) on its own executor thread, until `close()`. With
    `use_sim_time` its clock follows /clock."""

    def __init__(self, name, use_sim_time=False):
        overrides = [Parameter("use_sim_time", value=True)] if use_sim_time else []
        self.node = Node(name, parameter_overrides=overrides)
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self._stop = False
        self.errors = []
        self.thread = threading.Thread(target=self._spin, daemon=True)
        self.thread.start()

    def _spin(self):
        # An exception in one spin (a callback's, or rclpy's own) must not end the thread: every
        # later answer would then time out far from the cause. It is kept, spinning goes on, and
        # `_what` names it when an answer does not come.
        while not self._stop and rclpy.ok():
            try:
                self.executor.spin_once(timeout_sec=0.05)
            except Exception as e:
                if self._stop:
                    return
                if len(self.errors) < 20:
                    self.errors.append(repr(e)[:300])

    def _what(self, what):
        return f"{what} (peer spin errors: {self.errors})" if self.errors else what

    def now_ns(self):
        """The node's clock (simulated time with use_sim_time), ns."""
        return self.node.get_clock().now().nanoseconds

    def close(self):
        self._stop = True
        self.thread.join(timeout=5)
        self.executor.remove_node(self.node)
        self.node.destroy_node()
