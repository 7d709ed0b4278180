# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# fmt_statistics_globals (format_string): a format string walks statistics' globals to sys.modules['os'].environ at simulation time.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import statistics

behavior Payload():
    stolen = "{0.__init__.__globals__[sys].modules[os].environ[ARISE_HOSTILE_TOKEN]}".format(statistics.NormalDist())
    raise RuntimeError('stolen: ' + stolen)
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
