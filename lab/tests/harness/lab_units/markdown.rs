use stepladder_lab::report::markdown::*;

#[test]
fn table_renders_and_escapes_pipes() {
    let mut t = Table::new(&["a", "b"]);
    t.row(vec!["1".into(), "x|y".into()]);
    t.row(vec!["2".into()]);
    assert_eq!(
        t.render(),
        "| a | b |\n|---|---|\n| 1 | x\\|y |\n| 2 |  |\n"
    );
    assert_eq!(sci(0.000123456), "1.23e-4");
    assert_eq!(order(1.99949), "1.999");
}
#[test]
fn prose_is_wrapped_and_tables_are_not() {
    let long = "word ".repeat(60);
    let table = format!("| {} |\n", "cell ".repeat(40));
    let text = format!("{long}\n\n- {long}\n{table}```\n{long}\n```\n");
    let wrapped = wrap_prose(&text);
    let fenced = format!("```\n{long}\n```\n");
    assert!(wrapped.contains(&fenced), "a code block is kept whole");
    let outside = wrapped.replace(&fenced, "").replace(&table, "");
    for l in outside.lines() {
        assert!(l.chars().count() <= PROSE_WIDTH, "{l}");
    }
    assert!(wrapped.contains(&table), "the table is kept whole");
    // the words survive, in order
    let words = |s: &str| s.split_whitespace().map(str::to_string).collect::<Vec<_>>();
    assert_eq!(words(&wrapped), words(&text));
    // a list item's continuation sits under its text
    let item = wrapped.lines().find(|l| l.starts_with("- ")).unwrap();
    let after = wrapped.lines().skip_while(|l| *l != item).nth(1).unwrap();
    assert!(after.starts_with("  word"), "{after}");
}

#[test]
fn numbered_items_indent_under_their_text() {
    assert_eq!(list_indent("12. text"), 4);
    assert_eq!(list_indent("  - text"), 4);
    assert_eq!(list_indent("plain"), 0);
}
