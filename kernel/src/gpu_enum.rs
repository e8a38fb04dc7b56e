//! GPU-visible enums: declared once with [`gpu_enum!`](crate::gpu_enum!), stored in `Pod` records as `u32`.
//!
//! Every such enum is `#[repr(u32)]` (a default `u8` tag needs SPIR-V's Int8 capability)
//! and gets two decoders:
//! * host side, `TryFrom<u32>`: an unknown code is an [`UnknownVariant`] error naming the
//!   enum and the value — readers and backends validate with it before upload;
//! * GPU side, `from_u32`: an unknown code decodes to the variant the declaration names
//!   as `fallback` (the kernel cannot fail or panic; that code path is reached only by a
//!   record the host did not validate).

/// A `u32` that is not the code of any variant of a GPU-visible enum.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UnknownVariant {
    /// The enum's name.
    pub enum_name: &'static str,
    /// The code that was given.
    pub value: u32,
}

#[cfg(not(target_arch = "spirv"))]
impl core::fmt::Display for UnknownVariant {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{} is not a valid {} code", self.value, self.enum_name)
    }
}

#[cfg(not(target_arch = "spirv"))]
impl core::error::Error for UnknownVariant {}

/// Declares a GPU-visible enum: `#[repr(u32)]`, explicit codes, `TryFrom<u32>` for the host
/// `from_u32` with the named fallback for the GPU, and `From<Self> for u32` (see the module
/// documentation).
#[macro_export]
macro_rules! gpu_enum {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident {
            $( $(#[$vmeta:meta])* $variant:ident = $code:literal, )+
        }
        fallback = $fallback:ident;
    ) => {
        $(#[$meta])*
        #[repr(u32)]
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        $vis enum $name {
            $( $(#[$vmeta])* $variant = $code, )+
        }

        impl $name {
            #[doc = concat!("Decodes a `u32` on the GPU side: an unknown code reads as `",
                stringify!($fallback), "` (the host validates with `TryFrom` first).")]
            #[inline]
            pub fn from_u32(v: u32) -> $name {
                match v {
                    $( $code => $name::$variant, )+
                    _ => $name::$fallback,
                }
            }
        }

        impl From<$name> for u32 {
            #[inline]
            fn from(v: $name) -> u32 {
                v as u32
            }
        }

        impl core::convert::TryFrom<u32> for $name {
            type Error = $crate::gpu_enum::UnknownVariant;

            #[inline]
            fn try_from(v: u32) -> Result<$name, Self::Error> {
                match v {
                    $( $code => Ok($name::$variant), )+
                    _ => Err($crate::gpu_enum::UnknownVariant {
                        enum_name: stringify!($name),
                        value: v,
                    }),
                }
            }
        }
    };
}
