"""A Blender volume material as a Mirage shader (docs/blender.md, "Materials").

Cycles' Principled Volume (its GLSL and SVM code agree) gives, with density D times the density
attribute's value, scattering colour C and absorption colour A:
    sigma_s = C * D,   sigma_a = max(1 - C, 0) * max(1 - sqrt(A), 0) * D,
a Henyey-Greenstein phase of g = Anisotropy, and blackbody emission at the temperature
T = Temperature * the temperature attribute's value. Mirage's shader is a sum of components of
a grid slot times cross-sections: one component of sigma_s = C, sigma_a = (1 - C)(1 - sqrt(A))
on the slot "density" with the volume's density_scale = D does the same. Mirage's media emit
as Kirchhoff's law says, sigma_a * B(lambda, T) times `intensity`; Cycles' blackbody is
Stefan-Boltzmann's sigma T^4 / pi times Blackbody Intensity, independent of density. The
add-on sends T the same way (temperature_scale = Temperature) and Blackbody Intensity as the
intensity: 1 is "physical" in both, but a flame's brightness differs between the two.

What cannot be translated (other nodes, linked inputs, a constant emission colour) is named in
`left_out`; the shader is then the closest one built from the node's own values.
"""
import math

# The volume nodes whose inputs the closest shader reads when the material is not a lone
# Principled Volume: Cycles' Volume Scatter and Volume Absorption have the same Color, Density
# and Anisotropy sockets.
_VOLUME_NODES = ("ShaderNodeVolumePrincipled", "ShaderNodeVolumeScatter",
                 "ShaderNodeVolumeAbsorption")
_EMISSION_CUTOFF = 1e-5    # Cycles ignores emission and blackbody below these (its GLSL node)
_BLACKBODY_CUTOFF = 1e-3


class VolumeShader:
    """What a volume object's material becomes: a shader document, the slots bound to grids,
    the density scale, and the names of the nodes and inputs left out."""

    def __init__(self, name):
        self.name = name
        self.document = {"name": name}
        self.bind = {"density": "density"}
        self.density_scale = 1.0
        self.left_out = []


def value(node, socket, left_out):
    """A socket's own value; a link into it is left out (named) and its value used."""
    s = node.inputs.get(socket)
    if s is None:
        return None
    if s.is_linked:
        left_out.append(f"{node.name} › {socket} (linked from "
                        f"{', '.join(l.from_node.name for l in s.links)})")
    return s.default_value


def rgb(color):
    return [max(float(color[i]), 0.0) for i in range(3)]


def _sigma(rgb):
    """A cross-section as the shader file takes it: a number when grey (Mirage then keeps the
    medium wavelength-independent), else an RGB triple."""
    return rgb[0] if rgb[0] == rgb[1] == rgb[2] else rgb


def output_node(tree, socket="Volume"):
    """The node feeding the active Material Output's `socket` (None when unlinked)."""
    outputs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial"]
    active = [n for n in outputs if n.is_active_output and n.target in ("ALL", "CYCLES")]
    for out in active or outputs:
        sock = out.inputs.get(socket)
        if sock is not None and sock.is_linked:
            return sock.links[0].from_node
    return None


def _upstream(node):
    """Every node from `node` upstream, itself first (a depth-first walk of its links)."""
    seen, stack, order = set(), [node], []
    while stack:
        n = stack.pop()
        if n.name in seen:
            continue
        seen.add(n.name)
        order.append(n)
        for s in n.inputs:
            for link in s.links:
                stack.append(link.from_node)
    return order


def _component(color, density, absorption, anisotropy):
    """The one Mirage component of Cycles' Principled Volume (module docstring)."""
    root = [math.sqrt(a) for a in absorption]
    sigma_a = [max(1.0 - c, 0.0) * max(1.0 - r, 0.0) for c, r in zip(color, root)]
    return {"name": "medium", "grid": "density", "sigma_s": _sigma(color),
            "sigma_a": _sigma(sigma_a), "g": max(-0.99, min(0.99, float(anisotropy)))}


def _principled(node, shader, grids):
    """Principled Volume: scattering, absorption, anisotropy, blackbody emission."""
    lo = shader.left_out
    color = rgb(value(node, "Color", lo))
    absorption = rgb(value(node, "Absorption Color", lo))
    shader.density_scale = max(float(value(node, "Density", lo)), 0.0)
    density_attr = value(node, "Density Attribute", lo) or "density"
    shader.bind["density"] = density_attr
    shader.document["component"] = [
        _component(color, shader.density_scale, absorption, value(node, "Anisotropy", lo))]
    _blackbody(node, shader)
    if float(value(node, "Emission Strength", lo)) > _EMISSION_CUTOFF:
        lo.append(f"{node.name} › Emission Strength (Mirage media emit as blackbodies only)")
    color_attr = value(node, "Color Attribute", lo)
    if color_attr and color_attr in grids:
        lo.append(f"{node.name} › Color Attribute '{color_attr}'")


def _blackbody(node, shader):
    """Blackbody emission: T = Temperature × the temperature attribute, Kirchhoff in Mirage."""
    lo = shader.left_out
    intensity = float(value(node, "Blackbody Intensity", lo))
    if intensity <= _BLACKBODY_CUTOFF:
        return
    attr = value(node, "Temperature Attribute", lo)
    scale = float(value(node, "Temperature", lo))
    tint = rgb(value(node, "Blackbody Tint", lo))
    if tint != [1.0, 1.0, 1.0]:
        lo.append(f"{node.name} › Blackbody Tint")
    if not attr:
        lo.append(f"{node.name} › Blackbody Intensity without a Temperature Attribute")
        return
    shader.bind["temperature"] = attr
    shader.document["emission"] = {"temperature": "temperature", "temperature_scale": scale,
                                   "intensity": intensity}


def _closest(node, shader):
    """Volume Scatter or Absorption, or any node with their sockets: its colour, density and
    anisotropy as a Principled Volume's, reading the grid "density"."""
    lo = shader.left_out
    color = rgb(value(node, "Color", lo)) if node.inputs.get("Color") else [1.0, 1.0, 1.0]
    density = value(node, "Density", lo)
    shader.density_scale = max(float(density), 0.0) if density is not None else 1.0
    anisotropy = value(node, "Anisotropy", lo) or 0.0
    if node.bl_idname == "ShaderNodeVolumeAbsorption":
        color, absorption = [0.0, 0.0, 0.0], [1.0 - c for c in color]
    else:
        absorption = [0.0, 0.0, 0.0]
    shader.document["component"] = [_component(color, shader.density_scale, absorption,
                                                anisotropy)]


def translate(material, grids, name):
    """The Mirage shader of a Blender material on a volume whose file holds `grids`."""
    shader = VolumeShader(name)
    tree = material.node_tree if material is not None and material.use_nodes else None
    root = output_node(tree) if tree is not None else None
    if root is None:
        # No material, or nothing in its Volume socket: Cycles' default volume is a grey
        # Principled Volume of density 1 on "density" (its default material).
        shader.document["component"] = [_component([0.5] * 3, 1.0, [0.0] * 3, 0.0)]
        return shader
    nodes = _upstream(root)
    volume = next((n for n in nodes if n.bl_idname in _VOLUME_NODES), None)
    if volume is not None and volume.bl_idname == "ShaderNodeVolumePrincipled":
        _principled(volume, shader, grids)
    elif volume is not None:
        _closest(volume, shader)
    else:
        shader.document["component"] = [_component([0.5] * 3, 1.0, [0.0] * 3, 0.0)]
    for n in nodes:
        if n is not volume and n.bl_idname not in ("NodeReroute",):
            # Links into the volume node were named with their socket already.
            if not any(n.name in entry for entry in shader.left_out):
                shader.left_out.append(n.name)
    return shader
