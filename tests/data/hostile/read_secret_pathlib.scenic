# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# read_secret_pathlib (read_secret): pathlib.Path.read_text of a secret inside a require; the text leaks in the error.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import statistics
files = statistics.sys.modules['pathlib']

def leak(text):
    raise RuntimeError('stolen: ' + text)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require leak(files.Path('@SECRET@').read_text())
