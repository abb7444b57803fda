"""The Mirage-only physics of a volume material (Material Properties › Mirage Physics,
material.mirage), beside the translated Principled Volume: sea-water constituents (chlorophyll
and CDOM, with chlorophyll's fluorescence), fluorescence of the medium itself, and a refractive
index from the flame's temperature (heat haze). Each becomes what the scene file says for it
(docs/scene-file.md, "Shaders" and "Curved light"; docs/ocean-and-fluorescence.md)."""
import bpy


def _edited(settings, context):
    """A setting changed: the material's evaluated copy, the viewport and the next render
    follow (Blender tags an ID for its own properties' edits, not for an add-on's)."""
    settings.id_data.update_tag()


def _float(name, default, description, **limits):
    return bpy.props.FloatProperty(name=name, default=default, description=description,
                                   update=_edited, **limits)


def _switch(name, description, default=False):
    return bpy.props.BoolProperty(name=name, default=default, description=description,
                                  update=_edited)


class MirageMaterialSettings(bpy.types.PropertyGroup):
    use_chlorophyll: _switch(
        "Chlorophyll", "Phytoplankton's chlorophyll a (Bricaud et al. 1995 absorption, Gordon & "
        "Morel 1983 scattering), following the density attribute")
    chlorophyll: _float("Concentration", 1.0, "mg/m³ of chlorophyll a where the density "
                        "attribute is 1", min=0.0, soft_max=50.0, precision=3)
    chlorophyll_fluorescence: _float(
        "Fluorescence", 0.02, "Quantum efficiency of chlorophyll's fluorescence at 685 nm "
        "(0: none)", min=0.0, max=1.0, precision=3)
    use_cdom: _switch("CDOM", "Coloured dissolved organic matter: absorption "
                      "a_y(440) exp(-S (λ - 440))")
    cdom_covaries: _switch("From Chlorophyll", "Case-1 water: a_y(440) from the chlorophyll "
                           "(Morel & Maritorena 2001)", default=True)
    cdom_absorption: _float("Absorption at 440 nm", 0.05, "a_y(440) in 1/m where the density "
                            "attribute is 1 (Case-2 water)", min=0.0, precision=4)
    cdom_slope: _float("Slope", 0.014, "S in 1/nm", min=0.0, precision=4)
    fluorescence: _float("Fluorescence", 0.0, "Quantum efficiency of the medium's own "
                         "fluorescence, a dye (0: none)", min=0.0, max=1.0, precision=3)
    fluorescence_peak: _float("Peak", 520.0, "Emission peak, nm", min=360.0, max=830.0)
    fluorescence_width: _float("Width", 25.0, "Emission band's full width at half maximum, nm",
                               min=1.0, max=200.0)
    use_index_from_temperature: _switch(
        "Index from Temperature", "Heat haze: the air's refractive index from the blackbody "
        "temperature bends the camera's rays (Mirage's [refraction])")
    ambient_temperature: _float("Ambient", 288.15, "Kelvin of the air around", min=1.0)


def add_to_shader(material, shader, density_factor):
    """The panel's components on the translated shader (shading.VolumeShader). Their grid is
    the density slot, so a concentration is given per unit of the density attribute: divided
    by the volume's density_scale (the Principled Volume's Density × `density_factor`, the
    object-space factor), which Mirage multiplies every component by: a concentration is per
    cubic metre of the world, whatever the object's scale. Read from the original material:
    an evaluated copy may predate the last edit."""
    if material is None or shader.density_scale * density_factor <= 0.0:
        return
    s = material.original.mirage
    medium = shader.document["component"][0]
    if s.fluorescence > 0.0:
        medium.update(quantum_efficiency=s.fluorescence, emission_peak_nm=s.fluorescence_peak,
                      emission_fwhm_nm=s.fluorescence_width)
    per_density = 1.0 / (shader.density_scale * density_factor)
    if s.use_chlorophyll:
        shader.document["component"].append({
            "name": "chlorophyll", "kind": "chlorophyll", "grid": "density",
            "concentration": s.chlorophyll * per_density,
            "quantum_efficiency": s.chlorophyll_fluorescence})
    if s.use_cdom:
        cdom = {"name": "cdom", "kind": "cdom", "grid": "density", "slope": s.cdom_slope}
        if s.cdom_covaries and s.use_chlorophyll:
            cdom["covaries_with"] = "chlorophyll"
        else:
            cdom["concentration"] = s.cdom_absorption * per_density
        shader.document["component"].append(cdom)


def refraction(material, shader, volume, index, left_out):
    """The scene's [refraction] from the temperature of `volume`, the [[volume]] `index`, or
    None. The index follows the blackbody's temperature mapping, so the material needs one;
    and Mirage bends light through a grid only at a uniform scale and a translation: no
    rotation in Mirage's axes, which a Blender volume has unless its file is Y-up and stood up
    by +90° about X (docs/blender.md, "Axes")."""
    settings = material.original.mirage if material is not None else None
    if settings is None or not settings.use_index_from_temperature:
        return None
    why = None
    if "emission" not in shader.document:
        why = "needs Blackbody Intensity and a Temperature Attribute"
    elif abs(volume["transform"]["rotate"][0]) > 1e-3 or max(volume["transform"]["scale"]) > \
            min(volume["transform"]["scale"]) * (1.0 + 1e-6):
        why = ("Mirage bends light through a grid only unrotated in its axes, at one scale: "
               "a Y-up cache stood up +90° about X")
    if why:
        left_out.append(f"material '{material.name}': Index from Temperature ({why})")
        return None
    return {"profile": "grid", "volume": index, "ambient": settings.ambient_temperature}
