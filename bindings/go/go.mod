module mcstat/bindings/go

go 1.19
