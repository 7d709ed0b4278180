"""Offline stand-in for Scenic's CARLA world model, running on a Newtonian-style simulator.

Scripts written for ``model scenic.simulators.carla.model`` compile against
``arise.validate.worldmodel.model`` unchanged: same classes, blueprints, parameters,
actions and behaviors, but nothing ever connects to a CARLA server.
"""

MODEL_MODULE = "arise.validate.worldmodel.model"
