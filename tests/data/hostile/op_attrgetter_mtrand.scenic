# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# op_attrgetter_mtrand (module_attribute): operator.attrgetter (Scenic's vectors module -> numpy.random.mtrand.operator) takes the dotted name '_os.makedirs' as a string and walks it from random.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import scenic.core.vectors as vectors

walk = vectors.numpy.random.mtrand.operator.attrgetter('_os.makedirs')
walk(random)('@CANARY@', exist_ok=True)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
