# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# symlink_write_through (symlink): a dangling symlink beside the script (drop.txt -> the canary) written through at simulation time.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
DROP = localPath('.') / 'drop.txt'  # localPath itself would resolve the link

behavior Payload():
    if not numpy.lib._npyio_impl.os.path.islink(DROP):
        raise RuntimeError('drop.txt is not the planted link')
    numpy.savetxt(DROP, numpy.arange(3))
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
