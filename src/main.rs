fn main() {
    let mut bad = 0;
    let mut n = 0;
    for a in std::env::args().skip(1) {
        let mut map = bdi_check::syntax::SourceMap::new();
        n += 1;
        match bdi_check::syntax::load_agent(std::path::Path::new(&a), &mut map) {
            Ok(_) => {}
            Err(es) => {
                bad += 1;
                for e in es.iter().take(3) {
                    print!("{}", e.render(&map, false));
                }
            }
        }
    }
    println!("{bad} of {n} failed");
}
