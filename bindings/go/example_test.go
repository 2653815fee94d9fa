package mcstat_test

import (
	"errors"
	"fmt"

	mcstat "github.com/mcstat/mcstat/bindings/go"
)

// Does a new estimator agree with a trusted one?  Welch's t test of the
// difference of their means (R's t.test gives the same numbers).
func Example() {
	trusted := []float64{0.92, 1.04, 0.98, 1.11, 0.95, 1.02, 0.99, 1.07}
	newEst := []float64{1.01, 0.97, 1.12, 1.05, 0.94, 1.09, 1.03}
	r, err := mcstat.TTest2(newEst, trusted, 0, mcstat.TwoSided, 0.05)
	if errors.Is(err, mcstat.ErrDegenerate) {
		fmt.Println("constant data")
		return
	} else if err != nil {
		panic(err)
	}
	// fmt.Print(r.Format("new", "trusted")) prints R's t.test block
	fmt.Printf("decision %v, p = %.4f, df = %.3f\n", r.Decision, r.PValue, r.DF[0])
	fmt.Printf("95%% interval for the difference: [%.5f, %.5f]\n", r.ConfInt[0], r.ConfInt[1])
	// Output:
	// decision equal, p = 0.5515, df = 12.694
	// 95% interval for the difference: [-0.05081, 0.09081]
}

// A renderer checks its estimates as it renders: one Stream per goroutine,
// merged and checked at the end of a frame.
func ExampleStream() {
	s := mcstat.NewStream()
	for i := 0; i < 10000; i++ {
		u := (float64(i) + 0.5) / 10000 // stands for a pixel's Monte Carlo samples
		_ = s.Add(3 * u * u)            // estimates of the integral of 3u^2 over [0, 1], which is 1
	}
	r, err := s.CheckMean(1, 0, 0.01)
	if err != nil {
		panic(err)
	}
	fmt.Println("check failed:", r.Reject)
	// Output:
	// check failed: false
}
