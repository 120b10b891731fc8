# SPDX-License-Identifier: Apache-2.0
"""Deliberate faults of the volume agreement tests (test_volume_agreement.py,
test_volume_equiangular_agreement.py): wrappers of volumes.VolumeReader._value, each given the
original method and returning the faulty one."""


def anisotropy_ignored(original):
    def fault(self, node, name, kind):
        return 0.0 if name == "Anisotropy" else original(self, node, name, kind)
    return fault


def density_halved(original):
    def fault(self, node, name, kind):
        value = original(self, node, name, kind)
        return 0.5 * value if name == "Density" else value
    return fault
