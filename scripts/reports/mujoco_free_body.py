"""One free rigid body in MuJoCo (no gravity), for the peers' scripts that set it
beside ours (accuracy_peers, stability_peers); runs in the peers' venv."""
import mujoco

MJCF = """
<mujoco>
  <option gravity="0 0 0" timestep="{dt}" integrator="{integrator}"/>
  <worldbody>
    <body name="body">
      <freejoint/>
      <inertial pos="0 0 0" mass="1" diaginertia="{inertia}"/>
    </body>
  </worldbody>
</mujoco>
"""


def free_body_model(inertia, dt, integrator):
    """A 1 kg body of principal inertia `inertia` (kg m^2) on a free joint."""
    return mujoco.MjModel.from_xml_string(
        MJCF.format(dt=dt, integrator=integrator, inertia=" ".join(f"{v:g}" for v in inertia)))
