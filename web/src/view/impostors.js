// Sphere impostors for runs past 100,000 particles: one camera-facing quad per sphere on an
// InstancedBufferGeometry; the fragment shader casts the eye ray at the sphere, discards the
// pixels that miss it, shades the hit point and writes its true depth (gl_FragDepth), so spheres
// cut into each other, into plates and into force chains exactly as real geometry would.

import * as THREE from 'three';

const vertexShader = /* glsl */ `
attribute vec3 iCenter;
attribute float iRadius;
attribute vec3 iColour;
varying vec3 vCenter;   // sphere centre, view space
varying float vRadius;
varying vec3 vColour;
varying vec3 vPoint;    // this corner of the quad, view space
void main() {
  vec4 center = modelViewMatrix * vec4(iCenter, 1.0);
  // In perspective a sphere's outline is a little larger than its radius off the view axis; the
  // quad is enlarged so the outline stays inside it, and moved to the sphere's front so that it is
  // not clipped by the near plane before the sphere is.
  vec3 point = center.xyz + vec3(position.xy * iRadius * 1.5, iRadius);
  vCenter = center.xyz;
  vRadius = iRadius;
  vColour = iColour;
  vPoint = point;
  gl_Position = projectionMatrix * vec4(point, 1.0);
}
`;

const fragmentShader = /* glsl */ `
uniform mat4 projectionMatrix; // declared by three for the vertex stage only
uniform vec3 lightDirection; // towards the light, view space
uniform vec3 upDirection;    // world +z (the sky), view space
uniform float opacity;
uniform bool orthographic;   // parallel rays along -z instead of rays from the eye
varying vec3 vCenter;
varying float vRadius;
varying vec3 vColour;
varying vec3 vPoint;
void main() {
  // ray through this pixel, from the eye (the origin of view space) or, orthographic, along -z
  // from the pixel's point on the view plane z = 0: |o + t d - c|^2 = r^2
  vec3 o = orthographic ? vec3(vPoint.xy, 0.0) : vec3(0.0);
  vec3 d = orthographic ? vec3(0.0, 0.0, -1.0) : normalize(vPoint);
  vec3 oc = vCenter - o;
  float b = dot(d, oc);
  float h = b * b - dot(oc, oc) + vRadius * vRadius;
  if (h < 0.0) discard;
  float t = b - sqrt(h);
  vec3 hit = o + d * t;
  vec3 n = normalize(hit - vCenter);
  float diffuse = max(dot(n, lightDirection), 0.0);
  float sky = 0.5 + 0.5 * dot(n, upDirection); // a hemisphere term, as the sky light of the instanced spheres
  vec3 r = reflect(-lightDirection, n);
  float specular = pow(max(dot(r, -d), 0.0), 40.0) * 0.15;
  vec3 colour = vColour * (0.25 + 0.35 * sky + 0.7 * diffuse) + specular;
  vec4 clip = projectionMatrix * vec4(hit, 1.0);
  gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;
  gl_FragColor = vec4(colour, opacity);
  #include <colorspace_fragment>
}
`;

export class SphereImpostors {
  constructor(stage) {
    this.stage = stage;
    this.capacity = 0;
    this.active = false;
    this.hidden = false;
    this.material = new THREE.ShaderMaterial({
      vertexShader,
      fragmentShader,
      uniforms: {
        lightDirection: { value: new THREE.Vector3(0, 0, 1) },
        upDirection: { value: new THREE.Vector3(0, 0, 1) },
        opacity: { value: 1 },
        orthographic: { value: false },
      },
    });
    // The light moves with the camera in view space: refreshed before every draw.
    stage.beforeRender.push(() => {
      if (!this.active) return;
      const u = this.material.uniforms;
      stage.lightDirectionInView(u.lightDirection.value);
      u.upDirection.value.set(0, 0, 1).transformDirection(stage.camera.matrixWorldInverse);
      u.orthographic.value = stage.orthographic;
    });
  }

  ensure(count) {
    if (this.mesh && count <= this.capacity) return;
    if (this.mesh) {
      this.stage.scene.remove(this.mesh);
      this.mesh.geometry.dispose();
    }
    this.capacity = count;
    const g = new THREE.InstancedBufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute([-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0], 3));
    g.setIndex([0, 1, 2, 0, 2, 3]);
    this.centers = new THREE.InstancedBufferAttribute(new Float32Array(count * 3), 3).setUsage(THREE.DynamicDrawUsage);
    this.radii = new THREE.InstancedBufferAttribute(new Float32Array(count), 1).setUsage(THREE.DynamicDrawUsage);
    this.colours = new THREE.InstancedBufferAttribute(new Float32Array(count * 3), 3).setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('iCenter', this.centers);
    g.setAttribute('iRadius', this.radii);
    g.setAttribute('iColour', this.colours);
    this.mesh = new THREE.Mesh(g, this.material);
    this.mesh.frustumCulled = false;
    this.stage.scene.add(this.mesh);
  }

  draw(frame, visible, drawn, colours) {
    this.ensure(frame.count);
    const c = this.centers.array, r = this.radii.array, k3 = this.colours.array;
    const p = frame.positions;
    for (let k = 0; k < drawn; k++) {
      const i = visible[k];
      c[k * 3] = p[i * 3]; c[k * 3 + 1] = p[i * 3 + 1]; c[k * 3 + 2] = p[i * 3 + 2];
      r[k] = frame.radii[i];
      k3[k * 3] = colours[i * 3]; k3[k * 3 + 1] = colours[i * 3 + 1]; k3[k * 3 + 2] = colours[i * 3 + 2];
    }
    for (const [attribute, width] of [[this.centers, 3], [this.radii, 1], [this.colours, 3]]) {
      attribute.clearUpdateRanges();
      attribute.addUpdateRange(0, drawn * width);
      attribute.needsUpdate = true;
    }
    this.mesh.geometry.instanceCount = drawn;
    this.active = true;
    this.mesh.visible = !this.hidden && drawn > 0;
  }

  setOpacity(opacity) {
    this.material.uniforms.opacity.value = opacity;
    this.material.transparent = opacity < 1;
    this.material.depthWrite = opacity >= 1;
  }

  setVisible(on) {
    this.hidden = !on;
    if (this.mesh) this.mesh.visible = on && this.active;
  }

  hide() {
    this.active = false;
    if (this.mesh) this.mesh.visible = false;
  }
}
