#include "ParcelDeposition.H"
#include "Pstream.H"
#include "ops.H"
#include "mathematicalConstants.H"

#include <algorithm>
#include <thread>
#include <vector>

Foam::cosim::ParcelDeposition::ParcelDeposition(const fvMesh& mesh, label divisions)
:
    mesh_(mesh),
    locator_(mesh),
    satellites_(divisions),
    threads_
    (
        label(std::min(4u, std::max(1u, std::thread::hardware_concurrency())))
    )
{}


void Foam::cosim::ParcelDeposition::place
(
    const std::vector<std::int64_t>& ids,
    const std::vector<double>& position,
    const std::vector<double>& radius
)
{
    const label n = label(ids.size());
    const label nSat = satellites_.size();
    const label me = Pstream::myProcNo();
    const label nobody = labelMax;
    nParticles_ = n;

    auto centreOf = [&](label i)
    {
        return point(position[3*i], position[3*i + 1], position[3*i + 2]);
    };

    // 1. parcel centres, seeded by last step's cell
    centreCell_.setSize(n);
    labelList centreOwner(n, nobody);
    auto cursor = lastCell_.cbegin();
    auto seedOf = [&](std::int64_t id) -> label
    {
        const auto less = [](const std::pair<std::int64_t, label>& e, std::int64_t v)
        {
            return e.first < v;
        };
        // Ascending ids: the next one is at or after the cursor
        if (cursor == lastCell_.cend() || cursor->first > id)
        {
            cursor = lastCell_.cbegin();
        }
        cursor = std::lower_bound(cursor, lastCell_.cend(), id, less);
        return (cursor != lastCell_.cend() && cursor->first == id) ? cursor->second : -1;
    };
    for (label i = 0; i < n; ++i)
    {
        centreCell_[i] = locator_.locate(centreOf(i), seedOf(ids[i]));
        if (centreCell_[i] >= 0)
        {
            centreOwner[i] = me;
        }
    }
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(centreOwner, minEqOp<label>());
        Pstream::listCombineScatter(centreOwner);
    }
    lost_.setSize(n);
    lastCell_.clear();
    for (label i = 0; i < n; ++i)
    {
        if (centreOwner[i] != me)
        {
            centreCell_[i] = -1;
        }
        lost_[i] = (centreOwner[i] == nobody);
        if (centreCell_[i] >= 0)
        {
            lastCell_.emplace_back(ids[i], centreCell_[i]);
        }
    }
    if (!std::is_sorted(lastCell_.begin(), lastCell_.end()))
    {
        std::sort(lastCell_.begin(), lastCell_.end());
    }

    // 2. satellite points, seeded by the centre cell. Independent per parcel, so on one
    //    processor they are split over threads: the DEM waits for these samples, its core is
    //    free. Each point is located exactly as by one thread (same cells, same order of work
    //    within a parcel).
    labelList satCell(n*nSat, label(-1));
    labelList satOwner(n*nSat, nobody);
    auto satellitesOf = [&](label begin, label end)
    {
        for (label i = begin; i < end; ++i)
        {
            if (lost_[i])
            {
                continue;
            }
            const point c = centreOf(i);
            const scalar r = radius[i];
            const bool near = centreCell_[i] >= 0 || locator_.inBounds(c, r);
            if (!near)
            {
                continue;
            }
            // The whole parcel inside its centre cell (satellites lie within its radius):
            // each satellite's walk would end there at its first test
            if (centreCell_[i] >= 0 && locator_.holdsBall(c, r, centreCell_[i]))
            {
                for (label j = 0; j < nSat; ++j)
                {
                    satCell[i*nSat + j] = centreCell_[i];
                    satOwner[i*nSat + j] = me;
                }
                continue;
            }
            for (label j = 0; j < nSat; ++j)
            {
                const point x = c + r*satellites_.offsets()[j];
                label celli = -1;
                if (centreCell_[i] >= 0)
                {
                    celli = locator_.walk(x, centreCell_[i]);
                }
                if (celli < 0)
                {
                    celli = locator_.search(x);
                }
                if (celli >= 0)
                {
                    satCell[i*nSat + j] = celli;
                    satOwner[i*nSat + j] = me;
                }
            }
        }
    };
    const label nThreads = (Pstream::parRun() || n < 512) ? 1 : threads_;
    std::vector<std::thread> helpers;
    for (label t = 1; t < nThreads; ++t)
    {
        helpers.emplace_back(satellitesOf, n*t/nThreads, n*(t + 1)/nThreads);
    }
    satellitesOf(0, n/nThreads);
    for (std::thread& h : helpers)
    {
        h.join();
    }
    if (Pstream::parRun())
    {
        Pstream::listCombineGather(satOwner, minEqOp<label>());
        Pstream::listCombineScatter(satOwner);
    }

    // 3. deposits: owned satellites, plus orphans (outside the mesh) to the centre cell;
    //    one entry per cell of a parcel (its satellites' weights added in their order), so
    //    deposit and gatherAverage visit a few cells per parcel instead of every satellite
    start_.setSize(n + 1);
    depCell_.clear();
    depWeight_.clear();
    auto add = [&](label begin, label celli, scalar w)
    {
        for (label d = begin; d < depCell_.size(); ++d)
        {
            if (depCell_[d] == celli)
            {
                depWeight_[d] += w;
                return;
            }
        }
        depCell_.append(celli);
        depWeight_.append(w);
    };
    for (label i = 0; i < n; ++i)
    {
        const label begin = depCell_.size();
        start_[i] = begin;
        if (lost_[i])
        {
            continue;
        }
        scalar orphan = 0;
        for (label j = 0; j < nSat; ++j)
        {
            const label k = i*nSat + j;
            const scalar w = satellites_.weights()[j];
            if (satOwner[k] == me)
            {
                add(begin, satCell[k], w);
            }
            else if (satOwner[k] == nobody)
            {
                orphan += w;
            }
        }
        if (orphan > 0 && centreCell_[i] >= 0)
        {
            add(begin, centreCell_[i], orphan);
        }
    }
    start_[n] = depCell_.size();
}


void Foam::cosim::ParcelDeposition::deposit
(
    const UList<scalar>& perParticle,
    scalarField& cellSum
) const
{
    for (label i = 0; i < nParticles_; ++i)
    {
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            cellSum[depCell_[d]] += depWeight_[d]*perParticle[i];
        }
    }
}


void Foam::cosim::ParcelDeposition::deposit
(
    const UList<vector>& perParticle,
    vectorField& cellSum
) const
{
    for (label i = 0; i < nParticles_; ++i)
    {
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            cellSum[depCell_[d]] += depWeight_[d]*perParticle[i];
        }
    }
}


void Foam::cosim::ParcelDeposition::gatherAverage
(
    const UList<scalar>& cellField,
    List<scalar>& perParticle
) const
{
    perParticle.setSize(nParticles_);
    for (label i = 0; i < nParticles_; ++i)
    {
        scalar sum = 0;
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            sum += depWeight_[d]*cellField[depCell_[d]];
        }
        perParticle[i] = sum;
    }
}


void Foam::cosim::ParcelDeposition::gatherAverage
(
    const UList<vector>& cellField,
    List<vector>& perParticle
) const
{
    perParticle.setSize(nParticles_);
    for (label i = 0; i < nParticles_; ++i)
    {
        vector sum(Zero);
        for (label d = start_[i]; d < start_[i + 1]; ++d)
        {
            sum += depWeight_[d]*cellField[depCell_[d]];
        }
        perParticle[i] = sum;
    }
}
