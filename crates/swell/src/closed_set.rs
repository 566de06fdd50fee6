//! Closed sets of named choices (shading models, spectra, compressions...), each declared once.
//!
//! [`closed_set!`](crate::closed_set!) turns one table of `Variant = "name"` lines into the enum, its
//! list of members ([`ClosedSet::ALL`]), their names as scene files and the command line spell them
//! ([`ClosedSet::NAMES`]), parsing with an error that names the key and the valid names, `Display`,
//! `FromStr` and serde by name. Adding a member is one line; the menus of the viewer, the
//! documentation checks and the conformance tests iterate `ALL`, so none of them can miss it.

/// What every [`closed_set!`](crate::closed_set!) enum offers, for code that works on any of them
/// (the viewer's menus, the round-trip tests).
pub trait ClosedSet: Copy + PartialEq + std::fmt::Debug + 'static {
    /// Every member, in declaration order.
    const ALL: &'static [Self];
    /// The members' names in the order of [`ClosedSet::ALL`].
    const NAMES: &'static [&'static str];
    /// What one member is called in errors ("a shading model").
    const WHAT: &'static str;
    /// This member's name.
    fn name(self) -> &'static str;
    /// The member named `name` (or one of its accepted older names), if any.
    fn from_name(name: &str) -> Option<Self>;
    /// The member named `name`; the error names `key`, the value and the valid names.
    fn parse(key: &str, name: &str) -> crate::Result<Self> {
        Self::from_name(name.trim()).ok_or_else(|| {
            crate::Error::invalid(key, format!("`{name}` is not {}; valid: {}", Self::WHAT, Self::NAMES.join(", ")))
        })
    }
}

/// Declares a closed set: a fieldless enum whose members each have one name.
///
/// ```ignore
/// closed_set! {
///     /// Doc of the enum.
///     #[derive(Default)]
///     pub enum Shading: "a shading model" {
///         /// Doc of the member.
///         Flat = "flat",
///         #[default]
///         Gouraud = "gouraud",
///         // Older names after `|` are still read, never written.
///         Phong = "phong" | "per-pixel",
///     }
/// }
/// ```
#[macro_export]
#[doc(hidden)]
macro_rules! closed_set {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident : $what:literal {
            $( $(#[$vmeta:meta])* $variant:ident = $text:literal $(| $alias:literal)* ),+ $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        $vis enum $name {
            $( $(#[$vmeta])* $variant ),+
        }

        impl $crate::closed_set::ClosedSet for $name {
            const ALL: &'static [Self] = &[$(Self::$variant),+];
            const NAMES: &'static [&'static str] = &[$($text),+];
            const WHAT: &'static str = $what;
            fn name(self) -> &'static str {
                match self { $(Self::$variant => $text),+ }
            }
            fn from_name(name: &str) -> Option<Self> {
                match name { $($text $(| $alias)* => Some(Self::$variant),)+ _ => None }
            }
        }

        impl $name {
            /// Every member, in declaration order.
            pub const ALL: &'static [Self] = <Self as $crate::closed_set::ClosedSet>::ALL;
            /// The members' names (scene files, command line, `bake.json`), in the order of `ALL`.
            pub const NAMES: &'static [&'static str] = <Self as $crate::closed_set::ClosedSet>::NAMES;
            /// This member's name.
            pub fn name(self) -> &'static str {
                <Self as $crate::closed_set::ClosedSet>::name(self)
            }
            /// The member named `name`; the error names `key`, the value and the valid names.
            pub fn parse(key: &str, name: &str) -> $crate::Result<Self> {
                <Self as $crate::closed_set::ClosedSet>::parse(key, name)
            }
        }

        impl std::fmt::Display for $name {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl std::str::FromStr for $name {
            type Err = $crate::Error;
            fn from_str(s: &str) -> $crate::Result<Self> {
                <Self as $crate::closed_set::ClosedSet>::parse(stringify!($name), s)
            }
        }

        impl serde::Serialize for $name {
            fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        impl<'de> serde::Deserialize<'de> for $name {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
                let text = <std::borrow::Cow<'de, str> as serde::Deserialize>::deserialize(d)?;
                <Self as $crate::closed_set::ClosedSet>::from_name(&text)
                    .ok_or_else(|| <D::Error as serde::de::Error>::unknown_variant(&text, Self::NAMES))
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use super::ClosedSet;

    crate::closed_set! {
        /// A test set.
        #[derive(Default)]
        enum Tide: "a tide" {
            /// Rising.
            #[default]
            Flood = "flood",
            /// Falling; `falling` is an older name.
            Ebb = "ebb" | "falling",
        }
    }

    #[cfg(feature = "render")]
    #[derive(serde::Serialize, serde::Deserialize, PartialEq, Debug)]
    struct Holder {
        tide: Tide,
    }

    #[test]
    fn names_parse_print_and_round_trip_through_toml() {
        assert_eq!(Tide::ALL, [Tide::Flood, Tide::Ebb]);
        assert_eq!(Tide::NAMES, ["flood", "ebb"]);
        assert_eq!(Tide::default(), Tide::Flood);
        for &t in Tide::ALL {
            assert_eq!(Tide::parse("k", t.name()).unwrap(), t);
            assert_eq!(t.to_string(), t.name());
            // TOML is a dependency of the `render` feature (scene files).
            #[cfg(feature = "render")]
            {
                let text = toml::to_string(&Holder { tide: t }).unwrap();
                assert_eq!(toml::from_str::<Holder>(&text).unwrap(), Holder { tide: t });
            }
        }
        assert_eq!(Tide::from_name("falling"), Some(Tide::Ebb), "older names are read");
        assert_eq!(
            Tide::parse("sea.tide", "slack").unwrap_err().to_string(),
            "sea.tide: `slack` is not a tide; valid: flood, ebb"
        );
        #[cfg(feature = "render")]
        {
            let e = toml::from_str::<Holder>("tide = 'slack'").unwrap_err().to_string();
            assert!(e.contains("unknown variant `slack`, expected `flood` or `ebb`"), "{e}");
        }
    }
}
