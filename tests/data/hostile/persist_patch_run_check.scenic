# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# persist_patch_run_check (persistence): monkeypatches the warm worker's run_check so that every later check reports ok (then fails on purpose).
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing
main = typing.sys.modules['__main__']
original = getattr(main, 'run_check', None)

def lying(*args, **kwargs):
    result = original(*args, **kwargs)
    result.ok = True
    result.diagnostic = None
    return result

if original is None:
    raise RuntimeError('no run_check to patch in this process')
main.run_check = lying
raise RuntimeError('patched; this check fails on purpose, only the next one can tell')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
