// The glint layer's fields as EXT_materials_glint's schema gives them, which glint writes from its
// one table of the layer's fields (src/glint/glint_fields.h; `glint extension-schema`, taken by
// tools/build.mjs into generated/glint-fields.js): each property's kind, default and range. The
// plugin's checks and GlintLayer's defaults come from here, so that they cannot drift from glint's.
import schema from '../generated/glint-fields.js';

// The layer's own names where they differ from the extension's: GlintLayer is the kernel's
// GlintMaterial struct (kernel/glint_material.h), the shader's uniform, whose members keep the
// kernel's spelling.
const LAYER_NAMES = { densityRandomization: 'densityRandomisation', randomColors: 'colouredCells' };

// One entry per property of the extension but `extensions` and `extras`:
//   { name, field, kind: 'number' | 'pair' | 'integer' | 'boolean' | 'choice' | 'texture',
//     default, minimum, maximum, exclusiveMinimum, choices }
export const EXTENSION_FIELDS = Object.entries(schema.properties)
  .filter(([name]) => name !== 'extensions' && name !== 'extras')
  .map(([name, property]) => {
    const range = property.type === 'array' ? property.items : property;
    const kind = property.allOf ? 'texture'
      : property.type === 'array' ? 'pair'
      : property.type === 'string' ? 'choice'
      : property.type;
    return {
      name,
      field: LAYER_NAMES[name] || name,
      kind,
      default: property.default,
      minimum: range.exclusiveMinimum !== undefined ? range.exclusiveMinimum : range.minimum,
      maximum: range.maximum,
      exclusiveMinimum: range.exclusiveMinimum !== undefined,
      choices: property.enum,
    };
  });

export const EXTENSION_FIELD = Object.fromEntries(EXTENSION_FIELDS.map((f) => [f.name, f]));
