# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_multiprocessing (fork_exec): multiprocessing (fork context) starts a child that makes the canary.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import statistics
mp = statistics.sys.modules['importlib'].import_module('multiprocessing')
child = mp.get_context('fork').Process(target=random._os.mkdir, args=('@CANARY@',))
child.start()
child.join(10)
if child.exitcode != 0:
    raise RuntimeError(f'the child process ended with {child.exitcode}')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
