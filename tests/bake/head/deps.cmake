set(TEST_DEPS facial_bake facial eng_scene)
# Every suite reads the head generated once per process.
set(TEST_SUITES_IN_ONE_PROCESS HeadTextures HeadActionUnits HeadAsset HeadDeterminism HeadGeometry
    HeadLandmarkErrors HeadRigSpec HeadRigSpecErrors HeadShape)
