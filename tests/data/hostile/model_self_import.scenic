# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# model_self_import (model_map): a model line naming the script itself as a module (script.model_self_import.x): looking the model up imports the script as Python before the gate reads it.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
# The file is valid Python and valid Scenic; the test saves it as model_self_import.py.
Town = 'arise_straight'
if __name__.startswith('script.'):
    raise RuntimeError('PRE' + '-GATE-' + 'IMPORT')
"""
model script.model_self_import.x
"""
