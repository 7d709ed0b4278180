# Props and walkers: bus stop, vending machine, cones, a trash can and CARLA's AI walkers.
param map = localPath('../../../assets/maps/CARLA/Town02.xodr')
param carla_map = 'Town02'
model scenic.simulators.carla.model
param weather = 'HardRainNight'

ego = new Car on road, with behavior FollowLaneBehavior(target_speed=5)

stop = new BusStop on visible sidewalk, with regionContainedIn None
machine = new VendingMachine on visible sidewalk, with regionContainedIn None
cone1 = new Cone ahead of ego by 12
cone2 = new Cone ahead of cone1 by 2
trash = new Trash on visible sidewalk, with regionContainedIn None
barrier = new Barrier on road, with regionContainedIn None
walker1 = new Pedestrian on visible sidewalk, with behavior WalkBehavior()
walker2 = new Pedestrian on visible sidewalk, with behavior WalkForwardBehavior(speed=1.0)
cyclist = new Bicycle on road, with behavior FollowLaneBehavior(target_speed=3)
truck = new Truck on road, with behavior ConstantThrottleBehavior(0.3)

require (distance to intersection) > 20
terminate after 10 seconds
