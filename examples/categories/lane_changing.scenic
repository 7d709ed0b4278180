# Lane changing: a car in the next lane cuts in sharply just ahead of the ego.
# BEGIN HEADER
param map = localPath('../../maps/Town04.xodr')
param carla_map = 'Town04'
model scenic.simulators.carla.model
param weather = 'ClearSunset'
# END HEADER
# BEGIN BEHAVIOR
param OPT_ADV_SPEED = Range(10, 13)
param OPT_CUT_GAP = Range(6, 10)
behavior CutIn(targetSection):
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED) until (distance from self to ego) > globalParameters.OPT_CUT_GAP and (ego can see self)
    do LaneChangeBehavior(laneSectionToSwitch=targetSection, target_speed=globalParameters.OPT_ADV_SPEED)
    do FollowLaneBehavior(target_speed=globalParameters.OPT_ADV_SPEED - 4)
# END BEHAVIOR
# BEGIN GEOMETRY
multiLane = [s for lane in network.lanes for s in lane.sections if s._laneToLeft is not None and s._laneToLeft.isForward == s.isForward]
egoSection = Uniform(*multiLane)
egoStart = new OrientedPoint on egoSection.centerline
ego = new Car at egoStart, with behavior FollowLaneBehavior(target_speed=9)
# END GEOMETRY
# BEGIN SPAWN
param OPT_START_AHEAD = Range(2, 6)
advStart = new OrientedPoint left of egoStart by 3.5
adversary = new Car ahead of advStart by globalParameters.OPT_START_AHEAD, with behavior CutIn(egoSection)
# END SPAWN
# BEGIN REQUIREMENTS
require (distance to intersection) > 60
require adversary in egoSection._laneToLeft
terminate when (distance to egoStart) > 80
# END REQUIREMENTS
