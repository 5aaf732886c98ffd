//! What each bufferView is used for — vertex data, indices, images, inverse bind matrices or
//! other data — and the bufferView `target` that should say so (BUFFER_VIEW_TARGET_MISSING,
//! BUFFER_VIEW_TARGET_OVERRIDE); and what each accessor is used for, which must be one thing
//! (ACCESSOR_USAGE_OVERRIDE). Uses are met in the Khronos validator's link order, which
//! decides where a conflict is reported.

use crate::check::context::{elements, member, unsigned, Context};
use crate::diagnostic::khronos;
use crate::document::json::escape_token;
use crate::document::Node;
use crate::gltf::as_index;
use crate::gltf::gl;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Usage {
    Vertex,
    Index,
    Image,
    InverseBind,
    Other,
}

impl Usage {
    fn name(self) -> &'static str {
        match self {
            Usage::Vertex => "VertexBuffer",
            Usage::Index => "IndexBuffer",
            Usage::Image => "Image",
            Usage::InverseBind => "IBM",
            Usage::Other => "Other",
        }
    }
}

/// What an accessor is used for, by the validator's names.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum AccessorUsage {
    VertexAttribute,
    PrimitiveIndices,
    InverseBind,
    AnimationInput,
    AnimationOutput,
}

impl AccessorUsage {
    fn name(self) -> &'static str {
        match self {
            AccessorUsage::VertexAttribute => "VertexAttribute",
            AccessorUsage::PrimitiveIndices => "PrimitiveIndices",
            AccessorUsage::InverseBind => "IBM",
            AccessorUsage::AnimationInput => "AnimationInput",
            AccessorUsage::AnimationOutput => "AnimationOutput",
        }
    }
}

pub(super) fn check(ctx: &mut Context) {
    let usages = ctx
        .items("bufferViews")
        .iter()
        .map(|view| match unsigned(view, "target") {
            Some(gl::ARRAY_BUFFER) => Some(Usage::Vertex),
            Some(gl::ELEMENT_ARRAY_BUFFER) => Some(Usage::Index),
            _ => None,
        })
        .collect();
    let accessor_usages = vec![None; ctx.items("accessors").len()];
    let mut walk = Walk {
        ctx,
        usages,
        accessor_usages,
    };
    walk.sparse_accessors();
    walk.images();
    walk.meshes();
    walk.skins();
    walk.animations();
}

struct Walk<'c, 'a> {
    ctx: &'c mut Context<'a>,
    usages: Vec<Option<Usage>>,
    accessor_usages: Vec<Option<AccessorUsage>>,
}

impl Walk<'_, '_> {
    /// An accessor's use (its first one sets what it is for; `None`: its view's only), then
    /// its bufferView's.
    fn use_accessor(
        &mut self,
        index: Option<Node>,
        usage: Option<AccessorUsage>,
        view: Usage,
        at: String,
    ) {
        let accessor = index.and_then(as_index);
        let linked = accessor.filter(|&a| self.ctx.element("accessors", a).is_some());
        if let Some((a, usage)) = linked.zip(usage) {
            let slot = &mut self.accessor_usages[a as usize];
            match *slot {
                None => *slot = Some(usage),
                Some(previous) if previous != usage => self.ctx.emit(
                    khronos::ACCESSOR_USAGE_OVERRIDE,
                    at.clone(),
                    format!(
                        "Override of previously set accessor usage. Initial: '{}', new: '{}'.",
                        previous.name(),
                        usage.name()
                    ),
                ),
                Some(_) => {}
            }
        }
        let buffer_view = self.view_of(index);
        self.set(buffer_view, view, at);
    }

    fn set(&mut self, view: Option<u64>, usage: Usage, at: String) {
        // A reference to an element that is no bufferView object is unresolved: no usage.
        let Some(view) = view.filter(|&v| self.ctx.element("bufferViews", v).is_some()) else {
            return;
        };
        // A use marks the view used, also through an accessor the validator does not link
        // (one without a valid format still names its view).
        self.ctx.mark_used("bufferViews", view as usize);
        let Some(slot) = self.usages.get_mut(view as usize) else {
            return;
        };
        match *slot {
            None => {
                *slot = Some(usage);
                if matches!(usage, Usage::Vertex | Usage::Index) {
                    self.ctx.emit(
                        khronos::BUFFER_VIEW_TARGET_MISSING,
                        at,
                        "bufferView.target should be set for vertex or index data.",
                    );
                }
            }
            Some(previous) if previous != usage => self.ctx.emit(
                khronos::BUFFER_VIEW_TARGET_OVERRIDE,
                at,
                format!(
                    "Override of previously set bufferView target or usage. Initial: '{}', new: '{}'.",
                    previous.name(),
                    usage.name()
                ),
            ),
            Some(_) => {}
        }
    }

    /// The bufferView of the accessor that `index` names.
    fn view_of(&self, index: Option<Node>) -> Option<u64> {
        let accessor = self
            .ctx
            .items("accessors")
            .get(usize::try_from(as_index(index?)?).ok()?)?;
        unsigned(accessor, "bufferView")
    }

    fn sparse_accessors(&mut self) {
        for (_, pointer, accessor) in self.ctx.objects("accessors") {
            // Sparse parts are linked with their accessor, if it is linked at all.
            let sparse = accessor
                .get("sparse")
                .filter(|_| super::objects::is_linked(accessor));
            let Some(sparse) = sparse else {
                continue;
            };
            for part in ["indices", "values"] {
                let view = sparse.get(part).and_then(|p| unsigned(p, "bufferView"));
                let at = format!("{pointer}/sparse/{part}/bufferView");
                self.set(view, Usage::Other, at);
            }
        }
    }

    fn images(&mut self) {
        for (_, pointer, image) in self.ctx.objects("images") {
            let view = unsigned(image, "bufferView");
            self.set(view, Usage::Image, member(&pointer, "bufferView"));
        }
    }

    fn meshes(&mut self) {
        for (_, pointer, mesh) in self.ctx.objects("meshes") {
            for (p, primitive) in elements(mesh, "primitives") {
                let at = format!("{pointer}/primitives/{p}");
                let attributes = primitive.get("attributes").and_then(Node::as_object);
                let vertex = Some(AccessorUsage::VertexAttribute);
                for (semantic, index) in attributes.into_iter().flatten() {
                    let here = format!("{at}/attributes/{}", escape_token(semantic));
                    self.use_accessor(Some(index), vertex, Usage::Vertex, here);
                }
                let indices = primitive.get("indices");
                let here = member(&at, "indices");
                self.use_accessor(
                    indices,
                    Some(AccessorUsage::PrimitiveIndices),
                    Usage::Index,
                    here,
                );
                let targets = super::primitives::morph_targets(primitive);
                for (t, target) in targets.into_iter().flatten().enumerate() {
                    for (semantic, index) in target.as_object().into_iter().flatten() {
                        let here = format!("{at}/targets/{t}/{}", escape_token(semantic));
                        self.use_accessor(Some(index), vertex, Usage::Vertex, here);
                    }
                }
            }
        }
    }

    fn skins(&mut self) {
        for (_, pointer, skin) in self.ctx.objects("skins") {
            let matrices = skin.get("inverseBindMatrices");
            let at = member(&pointer, "inverseBindMatrices");
            let usage = Some(AccessorUsage::InverseBind);
            self.use_accessor(matrices, usage, Usage::InverseBind, at);
        }
    }

    fn animations(&mut self) {
        for (_, pointer, animation) in self.ctx.objects("animations") {
            let Some((samplers, _)) = super::animations::linked(animation) else {
                continue;
            };
            for (s, sampler) in samplers.iter().enumerate() {
                // The validator sets an output's view usage twice, so a conflicting target
                // is reported twice there (its accessor usage once).
                for (key, usage) in [
                    ("input", Some(AccessorUsage::AnimationInput)),
                    ("output", Some(AccessorUsage::AnimationOutput)),
                    ("output", None),
                ] {
                    let at = format!("{pointer}/samplers/{s}/{key}");
                    self.use_accessor(sampler.get(key), usage, Usage::Other, at);
                }
            }
        }
    }
}
