//! Issue 21: the README's library example is `examples/embed.rs`, which `cargo test` compiles:
//! the README shows the file from its first `use` on, so the two cannot drift apart.

#[test]
fn the_readme_library_example_is_the_compiled_embed_example() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let example = std::fs::read_to_string(format!("{root}/crates/swell/examples/embed.rs")).unwrap();
    let code = &example[example.find("use ").expect("embed.rs has a use line")..];
    let start = readme.find("## The library").expect("README has a library section");
    let block = &readme[start..];
    let open = block.find("```rust\n").expect("the library section has a rust block") + "```rust\n".len();
    let close = open + block[open..].find("```").unwrap();
    assert_eq!(
        &block[open..close],
        code,
        "README.md's library example differs from crates/swell/examples/embed.rs; paste the file from its first `use`"
    );
}
