# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# sock_udp_sendto (socket): a UDP datagram to loopback (Landlock has no UDP rules) in a `terminate when` expression.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import collections
net = collections._sys.modules['importlib'].import_module('socket')

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
terminate when net.socket(net.AF_INET, net.SOCK_DGRAM).sendto(b'hostile', ('127.0.0.1', @PORT@)) < 0
